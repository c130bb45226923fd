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
      // The default may differ (--pipeline: each technique's fastest); the help says each.
      EXPECT_EQ(option.derived, first.derived);
      EXPECT_EQ(option.min, first.min);
      EXPECT_EQ(option.max, first.max);
      EXPECT_EQ(option.choices, first.choices);
    }
  }
}

// Each technique's default pipeline is its fastest that gives the same bytes (README, "The
// default pipeline"): OPS's tiles march took 0.25-0.93 of the fast pipeline's time on every nk3
// dataset; RA's lost to RA's fast pipeline on teddybear at 512².
TEST(TechniqueTable, EachTechniqueDefaultsToItsFastestPipeline) {
  const std::map<std::string, std::string> expected{{"silhouette", "tiles"},
                                                    {"rightangle", "fast"}};
  for (const auto& technique : techniqueTable()) {
    const OptionSpec* pipeline = technique.option("pipeline");
    if (!pipeline) continue;
    ASSERT_TRUE(expected.contains(technique.name)) << technique.name << " has a pipeline";
    EXPECT_EQ(std::get<std::string>(*pipeline->defaultValue), expected.at(technique.name));
    EXPECT_FALSE(needsOneTexture(technique.name, {}))
        << technique.name << ": a default pipeline gives way to fast over bricks";
  }
  const auto help = test::runVsil("render --help");
  ASSERT_EQ(help.exitCode, 0) << help.err;
  EXPECT_NE(help.out.find("silhouette: default tiles (fast where the volume takes several "
                          "bricks: tiles needs one texture)"),
            std::string::npos)
      << help.out;
  EXPECT_NE(help.out.find("rightangle: default fast"), std::string::npos) << help.out;
}

// Over a volume in several bricks a default tiles pipeline gives way to fast; one asked for by
// name stays (and the frame refuses, or gets the volume again in one texture).
TEST(TechniqueTable, DefaultTilesGiveWayToFastOverBricks) {
  const TechniqueInfo& silhouette = findTechnique("silhouette");
  EXPECT_FALSE(optionsForBricks(silhouette, {}, 1).contains("pipeline"));
  EXPECT_EQ(std::get<std::string>(optionsForBricks(silhouette, {}, 2).at("pipeline")), "fast");
  const OptionValues tiles{{"pipeline", std::string("tiles")}};
  EXPECT_EQ(std::get<std::string>(optionsForBricks(silhouette, tiles, 2).at("pipeline")), "tiles");
  EXPECT_TRUE(needsOneTexture("silhouette", tiles));
  EXPECT_FALSE(optionsForBricks(findTechnique("rightangle"), {}, 2).contains("pipeline"));
  EXPECT_FALSE(optionsForBricks(findTechnique("mip"), {}, 2).contains("pipeline"));
}

// Across MPI ranks (a slab is never one texture): the silhouette's slab runs the fast pipeline
// whatever --pipeline says, so tiles asked for by name is no reason to refuse there; the other
// techniques' reasons stay (the CLI and the renderer both ask needsOneTextureInSlab).
TEST(TechniqueTable, ASlabNeedsOneTextureOnlyWhereItsFrameWould) {
  const OptionValues tiles{{"pipeline", std::string("tiles")}};
  const OptionValues exactHalo{{"effects", std::string("halo")},
                               {"halo-mode", std::string("exact")}};
  EXPECT_FALSE(findTechnique("silhouette").needsOneTextureInSlab(tiles));
  EXPECT_TRUE(findTechnique("rightangle").needsOneTextureInSlab(tiles));
  EXPECT_FALSE(findTechnique("rightangle").needsOneTextureInSlab({}));
  EXPECT_TRUE(findTechnique("illustrate").needsOneTextureInSlab(exactHalo));
  EXPECT_FALSE(findTechnique("illustrate").needsOneTextureInSlab({}));
  for (const auto& technique : techniqueTable()) {
    EXPECT_FALSE(technique.needsOneTextureInSlab({})) << technique.name << " at its defaults";
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
