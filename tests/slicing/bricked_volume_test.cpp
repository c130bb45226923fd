// A volume in one brick and in many (core/brick_layout.h, --max-texture-mib) renders the same
// bytes: state, depth, shade, tone and colour, for every technique and pipeline that takes
// bricks, and for the state techniques with the tone fill (the one screen pass besides the
// finishing one that samples the volume after the last slice; the fills none, flat and shaded
// are made from the state and shade). A case list checked against the technique table keeps a
// new technique, or a technique that gains the tone fill, from going untested.
// The brick borders cross the spheres' silhouettes, and the slice planes cross the borders at
// odd angles (perspective and orthographic views off every axis). What cannot follow the
// bricks (the tiles march, illustrate's exact halos) takes the volume in one texture when it
// fits and refuses with an InputError otherwise; illustrate's halo field (the default halo
// mode) is laid out per brick and renders the same bytes.
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/error.h"
#include "frame_compare.h"
#include "generators/generators.h"
#include "reference/gl_harness.h"
#include "slicing/renderer.h"
#include "slicing/technique_table.h"

namespace vsil {
namespace {

using test::GlTest;

// Bytes of one brick texture small enough for 4 or 5 bricks per axis of a 100³ volume (32³
// texels of R32F or smaller): 100 bricks (4·5·5, smaller ones at the ends).
constexpr std::uint64_t kSmallBrickBytes = 32 * 32 * 32 * 4;

struct TechniqueCase {
  std::string name;
  std::string technique;
  OptionValues options;
  std::optional<Rgba> toneFill;  // --fill tone
};

// The tone fill with what it reads besides the normal: two lights and distance blending (depth).
OptionValues withToneFillOptions(OptionValues options) {
  options["light"] = std::vector<std::string>{"30,50", "-70,-10"};
  options["param"] = std::vector<std::string>{"k_ds=0.5,k_de=0.7"};
  return options;
}
constexpr Rgba kToneFillColor{217, 199, 160, 255};

std::vector<TechniqueCase> techniqueCases() {
  auto iso = [](const std::string& technique) {
    return test::isoOptions(findTechnique(technique), 0.5);
  };
  auto with = [](OptionValues options, const std::string& key, const std::string& value) {
    options[key] = value;
    return options;
  };
  return {
      {"silhouette_paper", "silhouette", with(iso("silhouette"), "pipeline", "paper"),
       std::nullopt},
      {"silhouette_fast", "silhouette", with(iso("silhouette"), "pipeline", "fast"), std::nullopt},
      {"rightangle", "rightangle", iso("rightangle"), std::nullopt},
      {"silhouette_paper_tone", "silhouette",
       withToneFillOptions(with(iso("silhouette"), "pipeline", "paper")), kToneFillColor},
      {"silhouette_fast_tone", "silhouette",
       withToneFillOptions(with(iso("silhouette"), "pipeline", "fast")), kToneFillColor},
      {"rightangle_paper_tone", "rightangle",
       withToneFillOptions(with(iso("rightangle"), "pipeline", "paper")), kToneFillColor},
      {"rightangle_default_tone", "rightangle", withToneFillOptions(iso("rightangle")),
       kToneFillColor},
      {"firsthit", "firsthit", iso("firsthit"), std::nullopt},
      {"illustrate", "illustrate",
       with(iso("illustrate"), "effects", "boundary,silhouette,fading,sketch,distance,tone"),
       std::nullopt},
      {"illustrate_halo_field", "illustrate",
       with(iso("illustrate"), "effects", "boundary,silhouette,fading,sketch,distance,halo,tone"),
       std::nullopt},
      {"mip", "mip", iso("mip"), std::nullopt},
      {"demip", "demip", iso("demip"), std::nullopt},
      {"lmip", "lmip", iso("lmip"), std::nullopt},
      {"semantic", "semantic", iso("semantic"), std::nullopt},
  };
}

// Every technique has a case, and every technique that offers the tone fill (the state
// techniques that take --light: tone_fill.h withToneFillOptions) a case with it: what reads
// the volume after slicing is compared too.
TEST(BrickedVolumeCases, CoverEveryTechniqueAndTheToneFill) {
  const std::vector<TechniqueCase> cases = techniqueCases();
  for (const TechniqueInfo& info : techniqueTable()) {
    SCOPED_TRACE(info.name);
    const auto covered = [&](bool tone) {
      return std::any_of(cases.begin(), cases.end(), [&](const TechniqueCase& c) {
        return c.technique == info.name && c.toneFill.has_value() == tone;
      });
    };
    EXPECT_TRUE(covered(false)) << "a case without the tone fill";
    const bool offersToneFill = info.outputs.state && info.option("light") != nullptr;
    if (offersToneFill) {
      EXPECT_TRUE(covered(true)) << "a case with the tone fill";
    }
  }
}

void expectSameBytes(const cv::Mat& a, const cv::Mat& b, const std::string& what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  ASSERT_EQ(a.type(), b.type()) << what;
  if (a.empty()) return;
  ASSERT_TRUE(a.isContinuous() && b.isContinuous()) << what;
  const std::size_t bytes = a.total() * a.elemSize();
  if (std::memcmp(a.data, b.data, bytes) == 0) return;
  int differing = 0;
  for (int y = 0; y < a.rows; ++y) {
    for (int x = 0; x < a.cols; ++x) {
      if (std::memcmp(a.ptr(y, x), b.ptr(y, x), a.elemSize()) != 0) {
        if (differing++ < 3)
          ADD_FAILURE() << what << " differs at pixel (" << x << ", " << y << ")";
      }
    }
  }
  ADD_FAILURE() << what << ": " << differing << " pixels differ";
}

struct ViewCase {
  std::string name;
  double azimuth, elevation;
  bool orthographic;
};

class BrickedVolume : public GlTest {
 protected:
  static void SetUpTestSuite() { volume_ = new Volume(generateVolume("spheres:100")); }
  static void TearDownTestSuite() {
    delete volume_;
    volume_ = nullptr;
  }
  static Volume* volume_;
};
Volume* BrickedVolume::volume_ = nullptr;

TEST_F(BrickedVolume, ManyBricksRenderTheBytesOfOne) {
  Renderer whole(test::sharedGlContext()), bricked(test::sharedGlContext());
  whole.setVolume(*volume_);
  bricked.setVolume(*volume_, kSmallBrickBytes);
  ASSERT_EQ(whole.brickCount(), 1u);
  ASSERT_GE(bricked.brickCount(), 27u);
  for (const ViewCase& view :
       {ViewCase{"perspective", 23.0, 37.0, false}, ViewCase{"orthographic", -61.0, -17.0, true}}) {
    for (const TechniqueCase& c : techniqueCases()) {
      SCOPED_TRACE(c.name + ", " + view.name);
      RenderSettings settings;
      settings.technique = c.technique;
      settings.options = c.options;
      // One texture would run illustrate's default tiles march, whose colours equal the slice
      // passes' only to float rounding; the bricks run the fast pipeline (optionsForBricks).
      if (c.technique == "illustrate") settings.options["pipeline"] = std::string("fast");
      settings.toneFill = c.toneFill;
      settings.size = {88, 72};
      settings.samplesPerVoxel = 0.73;  // slice planes at odd positions
      settings.camera.azimuthDeg = view.azimuth;
      settings.camera.elevationDeg = view.elevation;
      settings.camera.orthographic = view.orthographic;
      const RenderResult one = whole.render(settings);
      const RenderResult many = bricked.render(settings);
      expectSameBytes(one.frame.state, many.frame.state, "state");
      expectSameBytes(one.frame.depth, many.frame.depth, "depth");
      expectSameBytes(one.frame.shade, many.frame.shade, "shade");
      expectSameBytes(one.frame.tone, many.frame.tone, "tone");
      expectSameBytes(one.frame.color, many.frame.color, "color");
      // Not trivially equal: something is shown.
      if (!one.frame.state.empty()) {
        EXPECT_GT(cv::countNonZero(one.frame.state), 100);
      }
      EXPECT_EQ(one.frame.tone.empty(), !c.toneFill.has_value());
    }
  }
}

TEST_F(BrickedVolume, WhatCannotFollowTheBricksRefuses) {
  Renderer bricked(test::sharedGlContext());
  bricked.setVolume(*volume_, kSmallBrickBytes);
  RenderSettings tiles;
  tiles.technique = "silhouette";
  tiles.options = test::isoOptions(findTechnique("silhouette"), 0.5);
  tiles.options["pipeline"] = std::string("tiles");
  tiles.size = {32, 32};
  EXPECT_THROW(bricked.render(tiles), InputError);
  RenderSettings halo;
  halo.technique = "illustrate";
  halo.options["effects"] = std::string("halo");
  halo.options["halo-mode"] = std::string("exact");
  halo.size = {32, 32};
  EXPECT_THROW(bricked.render(halo), InputError);
  // One brick: both render.
  Renderer whole(test::sharedGlContext());
  whole.setVolume(*volume_);
  EXPECT_NO_THROW(whole.render(tiles));
  EXPECT_NO_THROW(whole.render(halo));
}

// A volume that fits one texture but would waste more than half the texture limit to padding
// (260³ 8-bit: 512³ R16F texels, 256 MiB, under a 300 MiB limit) is cut into bricks of 256 + 8
// texels per axis; the tiles march, which cannot follow bricks, gets it in one texture and
// draws the pixels the fast pipeline draws on the bricks.
TEST(BrickedVolumeLayout, PaddedVolumeIsBrickedAndTilesGetItInOneTexture) {
  Volume volume;
  volume.source = "ball:260";
  volume.dims = glm::ivec3(260);
  volume.allocate(SampleType::UInt8);
  const std::span<std::uint8_t> samples = volume.samples<std::uint8_t>();
  const glm::dvec3 centre(141.0, 118.0, 127.0);  // off the brick border at 252
  for (int z = 0; z < 260; ++z) {
    for (int y = 0; y < 260; ++y) {
      for (int x = 0; x < 260; ++x) {
        const double r = glm::length(glm::dvec3(x, y, z) - centre);
        samples[volume.index(x, y, z)] = std::uint8_t(std::clamp(255.0 - 2.0 * r, 0.0, 255.0));
      }
    }
  }
  Renderer renderer(test::sharedGlContext());
  renderer.setVolume(volume, std::uint64_t(300) << 20);
  ASSERT_EQ(renderer.brickCount(), 8u);
  RenderSettings settings;
  settings.technique = "silhouette";
  settings.options = test::isoOptions(findTechnique("silhouette"), 40.0);
  settings.options["pipeline"] = std::string("fast");
  settings.size = {48, 40};
  settings.samplesPerVoxel = 0.37;
  settings.camera.azimuthDeg = 31.0;
  settings.camera.elevationDeg = 12.0;
  const RenderResult fast = renderer.render(settings);
  EXPECT_EQ(renderer.brickCount(), 8u);
  EXPECT_GT(cv::countNonZero(fast.frame.state), 100);
  settings.options["pipeline"] = std::string("tiles");
  const RenderResult tiles = renderer.render(settings);
  EXPECT_EQ(renderer.brickCount(), 1u);
  expectSameBytes(fast.frame.state, tiles.frame.state, "state");
  expectSameBytes(fast.frame.depth, tiles.frame.depth, "depth");
}

// A volume thinner than a brick's overlap along some axis (a DICOM series of 4x3x5 samples)
// takes one brick of 8³ texels and renders.
TEST(BrickedVolumeLayout, ThinVolumeRendersInOneSmallBrick) {
  Volume volume;
  volume.source = "thin";
  volume.dims = glm::ivec3(4, 3, 5);
  volume.allocate(SampleType::UInt8);
  const std::span<std::uint8_t> samples = volume.samples<std::uint8_t>();
  for (std::size_t i = 0; i < samples.size(); ++i) samples[i] = std::uint8_t(i % 7 * 40);
  Renderer renderer(test::sharedGlContext());
  renderer.setVolume(volume);
  EXPECT_EQ(renderer.brickCount(), 1u);
  RenderSettings settings;
  settings.technique = "silhouette";
  settings.options = test::isoOptions(findTechnique("silhouette"), 100.0);
  settings.size = {32, 32};
  const RenderResult result = renderer.render(settings);
  EXPECT_GT(cv::countNonZero(result.frame.state), 0) << "the thin volume shows";
}

}  // namespace
}  // namespace vsil
