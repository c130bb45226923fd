// `vsil bench --table semantic` on a small case: the plain composite, the four rule bases, the
// membership change and the rule change, measured and self-checked (a membership change compiles
// no program, a rule change one per frame), each with its frame-time ratio to the plain
// composite. No assertion on timings.
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "bench/bench_rows.h"
#include "test_support.h"

namespace vsil {
namespace {

TEST(SemanticTable, MeasuresEveryRuleBaseAndBothChangesWithTheirChecks) {
  VSIL_REQUIRE_DATASETS();
  const auto dir = test::scratchDir();
  const auto result = test::runVsil(
      "bench --table semantic --datasets " + test::datasetPath("").string() +
      " --only neghip --sizes 48 --frames 2 --warmup 0 --json " + (dir / "semantic.json").string());
  ASSERT_EQ(result.exitCode, 0) << result.err << result.out;
  EXPECT_NE(result.out.find("membership_change"), std::string::npos) << result.out;
  EXPECT_NE(result.out.find("×16 rules"), std::string::npos) << result.out;
  const auto json = nlohmann::json::parse(test::readFileBytes(dir / "semantic.json"));
  test::expectRowsRanOnTheReportedBackEnd(json);
  std::vector<std::string> cases;
  for (const auto& row : json["rows"]) {
    if (row["table"] != "semantic") continue;
    SCOPED_TRACE(row.dump());
    const std::string name = row["case"];
    cases.push_back(name);
    EXPECT_EQ(row["dataset"], "neghip");
    EXPECT_EQ(row["check"], "ok");
    EXPECT_EQ(row["frames"], 2);
    EXPECT_GT(row["fps"].get<double>(), 0.0);
    if (name == "plain") {
      EXPECT_EQ(row["technique"], "illustrate");
      continue;
    }
    EXPECT_EQ(row["technique"], "semantic");
    EXPECT_EQ(row["ratio_to"], "plain");
    EXPECT_GT(row["ratio"].get<double>(), 0.0);
    // Only a rule change compiles: once per timed frame.
    EXPECT_EQ(row["programs_compiled"], name == "rule_change" ? 2 : 0);
    if (name == "membership_change" || name == "rule_change") {
      EXPECT_EQ(row["rules"], 16);
      EXPECT_GT(row["ratio_to_rules_16"].get<double>(), 0.0);
      EXPECT_TRUE(row["extra_ms_median"].is_number());
    }
    if (name == "rules_16") {
      EXPECT_EQ(row["target"], 2.0);
      EXPECT_TRUE(row["target_met"].is_boolean());
    }
  }
  EXPECT_EQ(cases, (std::vector<std::string>{"plain", "rules_1", "rules_4", "rules_16", "rules_32",
                                             "membership_change", "rule_change"}));
}

}  // namespace
}  // namespace vsil
