// `vsil bench --table startup` end to end, through the built binary: one row per shader-cache
// setting with every stage of `vsil render --meta-out` in wall and CPU time, the stages within
// the process's time, and the self-check. No assertion on which stage is larger.
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "test_support.h"

namespace vsil {
namespace {

TEST(StartupTable, RowsCarryEveryStageWithinTheProcessTime) {
  VSIL_REQUIRE_DATASETS();
  const auto dir = test::scratchDir();
  const auto result = test::runVsil(
      "bench --table startup --only neghip --sizes 64 --frames 1 --warmup 0 --datasets " +
      test::datasetPath("").parent_path().string() + " --json " + (dir / "s.json").string());
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_NE(result.out.find("shader cache"), std::string::npos) << result.out;
  const auto rows = nlohmann::json::parse(test::readFileBytes(dir / "s.json"))["rows"];
  ASSERT_EQ(rows.size(), 2u) << rows.dump(1);
  EXPECT_EQ(rows[0]["shader_cache"], "on");
  EXPECT_EQ(rows[1]["shader_cache"], "off");
  for (const auto& row : rows) {
    SCOPED_TRACE(row.dump());
    EXPECT_EQ(row["table"], "startup");
    EXPECT_EQ(row["width"], 64);
    EXPECT_EQ(row["runs"], 1);
    EXPECT_EQ(row["check"], "ok");
    for (const char* kind : {"wall", "cpu"}) {
      const auto& stages = row[std::string("stages_") + kind + "_ms_median"];
      double sum = 0;
      for (const char* stage : {"startup", "context", "read", "upload", "defaults", "programs",
                                "render", "readback", "postfx", "write", "rest", "exit"}) {
        ASSERT_TRUE(stages[stage].is_number()) << kind << " " << stage;
        sum += stages[stage].get<double>();
      }
      // One run: the stages add up to the process's time (rest and exit close the gap).
      EXPECT_NEAR(sum, row[std::string("process_") + kind + "_ms_median"].get<double>(), 1e-6);
    }
    EXPECT_GT(row["stages_cpu_ms_median"]["defaults"].get<double>(), 0.0) << "no --iso given";
  }
}

}  // namespace
}  // namespace vsil
