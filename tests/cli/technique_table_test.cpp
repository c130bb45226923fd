// The table of techniques as the CLI reads it: every technique and option reaches `vsil render`,
// and an option two techniques declare means the same for both (the CLI has one flag for it).
#include <map>
#include <set>

#include <gtest/gtest.h>

#include "slicing/technique_table.h"
#include "test_support.h"

namespace vsil {
namespace {

TEST(TechniqueTable, NamesAreUniqueAndEachTechniqueReturnsSomething) {
  std::set<std::string> names;
  for (const auto& technique : techniqueTable()) {
    EXPECT_TRUE(names.insert(technique.name).second) << technique.name;
    EXPECT_FALSE(technique.summary.empty()) << technique.name;
    EXPECT_TRUE(technique.outputs.state || technique.outputs.color) << technique.name;
    EXPECT_TRUE(technique.create) << technique.name;
  }
}

TEST(TechniqueTable, AnOptionSharedByTechniquesMeansTheSameForAll) {
  std::map<std::string, std::pair<std::string, const OptionSpec*>> seen;
  for (const auto& technique : techniqueTable()) {
    for (const auto& option : technique.options) {
      const auto [it, added] = seen.try_emplace(option.name, technique.name, &option);
      if (added) continue;
      const OptionSpec& first = *it->second.second;
      SCOPED_TRACE("--" + option.name + " in " + it->second.first + " and " + technique.name);
      EXPECT_EQ(option.kind, first.kind);
      EXPECT_EQ(option.help, first.help);
      EXPECT_EQ(option.defaultValue, first.defaultValue);
      EXPECT_EQ(option.derived, first.derived);
      EXPECT_EQ(option.min, first.min);
      EXPECT_EQ(option.max, first.max);
      EXPECT_EQ(option.choices, first.choices);
    }
  }
}

TEST(TechniqueTable, RenderHelpListsEveryTechniqueAndOption) {
  const auto help = test::runVsil("render --help");
  ASSERT_EQ(help.exitCode, 0) << help.err;
  for (const auto& technique : techniqueTable()) {
    EXPECT_NE(help.out.find(technique.name), std::string::npos) << technique.name;
    for (const auto& option : technique.options) {
      EXPECT_NE(help.out.find(option.flag()), std::string::npos) << option.flag();
    }
  }
}

}  // namespace
}  // namespace vsil
