// `vsil bench --table dv1` on a small case: the four columns per dataset (MIP, DEMIP, DEMIP with
// the sphere, DVR), measured and self-checked, with the paper's numbers where it measured the
// same dataset.
#include <filesystem>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

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
  for (const auto& row : json["rows"]) {
    if (row["table"] != "dv1") continue;
    ++measured;
    EXPECT_EQ(row["check"], "ok") << row.dump();
    EXPECT_GT(row["fps"].get<double>(), 0.0) << row.dump();
    EXPECT_GT(row["cpu_ms_median"].get<double>(), 0.0) << row.dump();
    EXPECT_EQ(row["frames"], 2);
    // The paper measured only the aneurysm of these, and only at 512².
    EXPECT_TRUE(row["paper_fps"].is_null()) << row.dump();
  }
  EXPECT_EQ(measured, 8) << "two datasets, four columns";
}

}  // namespace
}  // namespace vsil
