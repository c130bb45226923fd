// The table of techniques as the CLI reads it: every technique and option reaches `vsil render`,
// and an option two techniques declare means the same for both (the CLI has one flag for it).
#include <map>
#include <set>

#include <gtest/gtest.h>

#include "core/camera.h"
#include "slicing/slab.h"
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
// dataset; RA's took 0.41-0.81 of RA fast's on all five nk3 datasets at 256² and 512² on a quiet
// machine (2026-12-06; on a loaded one it had lost on teddybear at 512²).
TEST(TechniqueTable, EachTechniqueDefaultsToItsFastestPipeline) {
  const std::map<std::string, std::string> expected{
      {"silhouette", "tiles"}, {"rightangle", "tiles"}, {"illustrate", "tiles"}};
  for (const auto& technique : techniqueTable()) {
    const OptionSpec* pipeline = technique.option("pipeline");
    if (!pipeline) continue;
    ASSERT_TRUE(expected.contains(technique.name)) << technique.name << " has a pipeline";
    EXPECT_EQ(std::get<std::string>(*pipeline->defaultValue), expected.at(technique.name));
    EXPECT_FALSE(technique.needsOneTextureWith({}))
        << technique.name << ": a default pipeline gives way to fast over bricks";
  }
  const auto help = test::runVsil("render --help");
  ASSERT_EQ(help.exitCode, 0) << help.err;
  // One default for the three, so the help states it once.
  EXPECT_NE(help.out.find("(default tiles (fast where the volume takes several bricks: tiles "
                          "needs one texture), fast | paper | tiles)"),
            std::string::npos)
      << help.out;
}

// Over a volume in several bricks a default tiles pipeline gives way to fast; one asked for by
// name stays (and the frame refuses, or gets the volume again in one texture).
TEST(TechniqueTable, DefaultTilesGiveWayToFastOverBricks) {
  const TechniqueInfo& silhouette = findTechnique("silhouette");
  EXPECT_FALSE(optionsForBricks(silhouette, {}, 1).contains("pipeline"));
  EXPECT_EQ(std::get<std::string>(optionsForBricks(silhouette, {}, 2).at("pipeline")), "fast");
  const OptionValues tiles{{"pipeline", std::string("tiles")}};
  EXPECT_EQ(std::get<std::string>(optionsForBricks(silhouette, tiles, 2).at("pipeline")), "tiles");
  EXPECT_TRUE(silhouette.needsOneTextureWith(tiles));
  EXPECT_EQ(
      std::get<std::string>(optionsForBricks(findTechnique("rightangle"), {}, 2).at("pipeline")),
      "fast");
  EXPECT_EQ(
      std::get<std::string>(optionsForBricks(findTechnique("illustrate"), {}, 2).at("pipeline")),
      "fast");
  EXPECT_FALSE(optionsForBricks(findTechnique("mip"), {}, 2).contains("pipeline"));
}

// A slab's frame runs fast where no pipeline was given, and whatever was given where the
// table says slabRunsFastPipeline (silhouette, illustrate); the renderer runs and records these.
TEST(TechniqueTable, ASlabRunsFastWhereTheTableSays) {
  const auto pipelineInSlab = [](const std::string& technique, const OptionValues& given) {
    const OptionValues slab = optionsForSlab(findTechnique(technique), given);
    return slab.contains("pipeline") ? std::get<std::string>(slab.at("pipeline")) : "";
  };
  const OptionValues tiles{{"pipeline", std::string("tiles")}};
  const OptionValues paper{{"pipeline", std::string("paper")}};
  for (const char* technique : {"silhouette", "rightangle", "illustrate"}) {
    EXPECT_EQ(pipelineInSlab(technique, {}), "fast") << technique;
  }
  EXPECT_EQ(pipelineInSlab("silhouette", tiles), "fast");
  EXPECT_EQ(pipelineInSlab("silhouette", paper), "fast");
  EXPECT_EQ(pipelineInSlab("illustrate", tiles), "fast");
  EXPECT_EQ(pipelineInSlab("rightangle", paper), "paper");
  EXPECT_EQ(pipelineInSlab("rightangle", tiles), "tiles");  // refused: needsOneTextureInSlab
  EXPECT_EQ(pipelineInSlab("mip", {}), "");
}

// Across MPI ranks (a slab is never one texture): the silhouette's and illustrate's slabs run
// the fast pipeline whatever --pipeline says, so tiles asked for by name is no reason to refuse
// there; the other techniques' reasons stay (the CLI and the renderer both ask
// needsOneTextureInSlab).
TEST(TechniqueTable, ASlabNeedsOneTextureOnlyWhereItsFrameWould) {
  const OptionValues tiles{{"pipeline", std::string("tiles")}};
  const OptionValues exactHalo{{"effects", std::string("halo")},
                               {"halo-mode", std::string("exact")}};
  EXPECT_FALSE(findTechnique("silhouette").needsOneTextureInSlab(tiles));
  EXPECT_FALSE(findTechnique("illustrate").needsOneTextureInSlab(tiles));
  EXPECT_TRUE(findTechnique("rightangle").needsOneTextureInSlab(tiles));
  EXPECT_FALSE(findTechnique("rightangle").needsOneTextureInSlab({}));
  EXPECT_TRUE(findTechnique("illustrate").needsOneTextureInSlab(exactHalo));
  EXPECT_FALSE(findTechnique("illustrate").needsOneTextureInSlab({}));
  for (const auto& technique : techniqueTable()) {
    EXPECT_FALSE(technique.needsOneTextureInSlab({})) << technique.name << " at its defaults";
  }
}

// A slab's ghost width (slab.h techniqueGhostVoxels) is the table's: what each technique reads
// beside its samples. illustrate's halo field reads ceil(k_hr) + 2 voxels beyond an owned
// brick's texels (halo_mask.h haloFieldReachVoxels), plus 4; without halos, the gradients alone
// (2, as semantic). silhouette's grows as a pixel spans more voxels (zoomed out).
TEST(TechniqueTable, ASlabsGhostWidthFollowsWhatTheTechniqueReads) {
  const glm::ivec3 dims(64);
  const auto viewAt = [&](double zoom) {
    return makeView(CameraSpec{.azimuthDeg = 37, .elevationDeg = -23, .zoom = zoom}, dims,
                    glm::dvec3(1.0), {96, 96});
  };
  const View view = viewAt(1.6);
  const auto ghost = [&](const std::string& technique, const OptionValues& given = {}) {
    return techniqueGhostVoxels(findTechnique(technique), given, view, dims);
  };
  for (const char* name : {"mip", "demip", "lmip", "rightangle", "firsthit"}) {
    EXPECT_EQ(ghost(name), 0) << name;
  }
  EXPECT_EQ(ghost("semantic"), 2);
  EXPECT_EQ(ghost("illustrate"), 2);
  const auto halos = [](const std::string& params) {
    return OptionValues{{"effects", std::string("halo")},
                        {"param", std::vector<std::string>{params}}};
  };
  EXPECT_EQ(ghost("illustrate", {{"effects", std::string("halo")}}), 10);  // k_hr 4
  EXPECT_EQ(ghost("illustrate", halos("k_hr=6.5")), 13);
  EXPECT_EQ(ghost("illustrate", halos("k_hr=32")), 38);  // the largest radius
  const int near = ghost("silhouette");
  const int far = techniqueGhostVoxels(findTechnique("silhouette"), {}, viewAt(0.3), dims);
  EXPECT_GE(near, 2);
  EXPECT_GT(far, near);
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
