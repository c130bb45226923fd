// `vsil bench --table fft` end to end, through the built binary: two JSON rows per size and
// sigma, the printed and Markdown tables with their self-check column. No assertion on timings.
#include <set>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "test_support.h"

namespace vsil {
namespace {

TEST(FftTable, RowsAndTablesForEverySigma) {
  const auto dir = test::scratchDir();
  const auto result =
      test::runVsil("bench --table fft --sizes 32 --frames 2 --json " +
                    (dir / "fft.json").string() + " --markdown " + (dir / "fft.md").string());
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_NE(result.out.find("size  sigma  FFT ms"), std::string::npos) << result.out;

  const auto rows = nlohmann::json::parse(test::readFileBytes(dir / "fft.json"))["rows"];
  ASSERT_EQ(rows.size(), 12u) << "1 size x 6 sigmas x (fft, spatial)\n" << rows.dump(1);
  std::set<std::pair<double, std::string>> seen;
  for (const auto& row : rows) {
    SCOPED_TRACE(row.dump());
    EXPECT_EQ(row["table"], "fft");
    EXPECT_EQ(row["width"], 32);
    EXPECT_EQ(row["frames"], 2);
    EXPECT_EQ(row["check"], "ok");
    EXPECT_LE(row["ms_min"].get<double>(), row["ms_median"].get<double>());
    EXPECT_LE(row["ms_median"].get<double>(), row["ms_max"].get<double>());
    seen.insert({row["sigma"].get<double>(), row["technique"].get<std::string>()});
  }
  EXPECT_EQ(seen.size(), 12u) << "each sigma once per filter";

  const std::string markdown = test::readFileBytes(dir / "fft.md");
  EXPECT_NE(markdown.find("| size | sigma | FFT ms |"), std::string::npos) << markdown;
  EXPECT_NE(markdown.find("| 32² | 32 |"), std::string::npos) << markdown;
}

}  // namespace
}  // namespace vsil
