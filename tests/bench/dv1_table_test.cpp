// `vsil bench --table dv1` on a small case: the four columns per dataset (MIP, DEMIP, DEMIP with
// the sphere, DVR), measured and self-checked, with the paper's numbers where it measured the
// same dataset.
#include <filesystem>
#include <map>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "bench/bench_rows.h"
#include "test_support.h"

namespace vsil {
namespace {

TEST(Dv1Table, MeasuresAndChecksMipDemipTheSphereAndDvr) {
  VSIL_REQUIRE_DATASETS();
  const auto dir = test::scratchDir();
  const auto result =
      test::runVsil("bench --table dv1 --datasets " + test::datasetPath("").string() +
                    " --only teddybear,aneurism --sizes 48 --frames 2 --warmup 0 --json " +
                    (dir / "dv1.json").string());
  ASSERT_EQ(result.exitCode, 0) << result.err << result.out;
  EXPECT_NE(result.out.find("DEMIP/MIP"), std::string::npos) << result.out;
  EXPECT_NE(result.out.find("cpu DEMIP/MIP"), std::string::npos) << result.out;
  EXPECT_NE(result.out.find("Aneurysm 512²·120 76.2 / 54.5"), std::string::npos) << result.out;
  const auto json = nlohmann::json::parse(test::readFileBytes(dir / "dv1.json"));
  int measured = 0;
  std::map<std::string, nlohmann::json> mipOf;  // dataset -> its MIP row
  for (const auto& row : json["rows"]) {
    if (row["technique"] == "mip") mipOf[row["dataset"]] = row;
  }
  for (const auto& row : json["rows"]) {
    if (row["table"] != "dv1") continue;
    ++measured;
    // DEMIP, DEMIP+sphere and DVR to MIP, frame by frame: the median of the two turns' quotients.
    ASSERT_EQ(row["ms"].size(), 2u) << row.dump();
    if (row["technique"] != "mip") {
      const auto& mip = mipOf.at(row["dataset"])["ms"];
      EXPECT_EQ(row["ratio_to"], "mip");
      EXPECT_NEAR(row["ratio"].get<double>(),
                  0.5 * (row["ms"][0].get<double>() / mip[0].get<double>() +
                         row["ms"][1].get<double>() / mip[1].get<double>()),
                  1e-9)
          << row.dump();
    }
    EXPECT_EQ(row["check"], "ok") << row.dump();
    EXPECT_GT(row["fps"].get<double>(), 0.0) << row.dump();
    EXPECT_GT(row["cpu_ms_median"].get<double>(), 0.0) << row.dump();
    EXPECT_EQ(row["frames"], 2);
    // The paper measured only the aneurysm of these, and only at 512².
    EXPECT_TRUE(row["paper_fps"].is_null()) << row.dump();
  }
  EXPECT_EQ(measured, 8) << "two datasets, four columns";
  test::expectRowsRanOnTheReportedBackEnd(json);
}

}  // namespace
}  // namespace vsil
