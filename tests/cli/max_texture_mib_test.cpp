// `vsil render --max-texture-mib N` through the built binary: gen:spheres:128 (float32, an 8 MiB
// R32F texture) in bricks of at most 1 MiB (11 bricks of 16x128x128 texels, the fewest texels)
// gives the same PNG, state and depth bytes as in one texture, with every --fill (tone's screen
// pass samples the volume after the last slice); what cannot follow the bricks
// (--pipeline tiles, asked for by name) refuses with one line, exit 2 and no output file, while
// silhouette's default tiles pipeline gives way to fast; the flag's range is checked.
#include <filesystem>
#include <sstream>
#include <string>
#include <tuple>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "reference/test_support.h"

namespace vsil {
namespace {

namespace fs = std::filesystem;

// stderr less the progress lines a load still running after a second writes
// (cli/cli_progress.h: "vsil: uploading the volume ...\n"), which a busy machine shows.
std::string withoutProgressLines(const std::string& err) {
  std::istringstream lines(err);
  std::string kept, line;
  while (std::getline(lines, line)) {
    const bool progress = line.starts_with("vsil: ") && line.ends_with(" ...");
    if (!progress) kept += line + "\n";
  }
  return kept;
}

// The output bytes, and `--meta-out`'s volume_texture into `texture` and the pipeline used into
// `pipeline` (null for techniques without one).
std::string render(const fs::path& dir, const std::string& name, const std::string& flags,
                   nlohmann::json& texture, nlohmann::json& pipeline) {
  const std::string base = (dir / name).string();
  const auto result = test::runVsil("render gen:spheres:128 " + flags +
                                    " --size 96x80 --view 37,-23 --sampling 0.9 --out " + base +
                                    ".png --state-out " + base + "-state.png --depth-out " + base +
                                    "-depth.png --meta-out " + base + ".json");
  EXPECT_EQ(result.exitCode, 0) << result.err;
  EXPECT_EQ(withoutProgressLines(result.err), "") << "no warnings";
  const auto meta = nlohmann::json::parse(test::readFileBytes(base + ".json"));
  texture = meta["volume_texture"];
  pipeline = meta["parameters"]["pipeline"];
  return test::readFileBytes(base + ".png") + "|" + test::readFileBytes(base + "-state.png") + "|" +
         test::readFileBytes(base + "-depth.png");
}

// The default pipeline of silhouette and rightangle, tiles, gives way to fast over the bricks (the
// same bytes).
TEST(MaxTextureMib, BricksRenderTheBytesOfOneTextureAndTheMetadataSaysSo) {
  const fs::path dir = test::scratchDir();
  for (const auto& [technique, wholePipeline, brickedPipeline] :
       {std::tuple{"--technique silhouette --pipeline paper", "paper", "paper"},
        std::tuple{"--technique silhouette", "tiles", "fast"},
        std::tuple{"--technique rightangle", "tiles", "fast"}}) {
    for (const std::string fill :
         {"--fill none", "--fill flat", "--fill shaded",
          "--fill tone --fill-color '#d9c7a0' --light 30,50 --light -70,-10 --param k_ds=0.5"}) {
      const std::string flags = std::string(technique) + " " + fill;
      SCOPED_TRACE(flags);
      nlohmann::json wholeTexture, brickedTexture, wholeUsed, brickedUsed;
      const std::string whole = render(dir, "whole", flags, wholeTexture, wholeUsed);
      const std::string bricked =
          render(dir, "bricked", flags + " --max-texture-mib 1", brickedTexture, brickedUsed);
      EXPECT_TRUE(whole == bricked) << "the PNG, state or depth bytes differ";
      EXPECT_EQ(wholeTexture, nlohmann::json({{"format", "R32F"}, {"bricks", {1, 1, 1}}}));
      EXPECT_EQ(brickedTexture, nlohmann::json({{"format", "R32F"}, {"bricks", {1, 1, 11}}}));
      EXPECT_EQ(wholeUsed, wholePipeline);
      EXPECT_EQ(brickedUsed, brickedPipeline);
    }
  }
}

TEST(MaxTextureMib, TilesRefuseBricksWithOneLineAndNoFile) {
  const fs::path dir = test::scratchDir();
  const fs::path out = dir / "tiles.png";
  const auto result = test::runVsil(
      "render gen:spheres:128 --pipeline tiles --max-texture-mib 1 --size 32x32 --out " +
      out.string());
  EXPECT_EQ(result.exitCode, 2);
  EXPECT_EQ(result.err,
            "vsil: --pipeline tiles needs the volume in one texture, and this volume takes 11 "
            "bricks (1x1x11); use --pipeline fast or paper (the same pixels)\n");
  EXPECT_FALSE(fs::exists(out));
}

TEST(MaxTextureMib, IsCheckedBeforeAnyWork) {
  for (const std::string value : {"0", "1809"}) {
    const auto result =
        test::runVsil("render gen:sphere:16 --max-texture-mib " + value + " --out /dev/null");
    EXPECT_EQ(result.exitCode, 2) << value;
    EXPECT_EQ(result.err,
              "vsil: --max-texture-mib " + value + ": must be between 1 and 1808 MiB\n");
  }
}

}  // namespace
}  // namespace vsil
