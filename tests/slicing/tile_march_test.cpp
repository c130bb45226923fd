// The tile march (slicing/tile_march.h, --pipeline tiles) where it works differently from the
// passes per slice: frames whose slices take several dispatches, images that end inside a tile
// or are smaller than one, and views where tiles start and stop at different slices. The passes
// per slice (the fast pipeline) are the yardstick: every pixel's state, depth and shade the
// same. (Every pipeline against the CPU reference on every scene, surfaces that meet the box's
// faces included: gl_vs_reference_test.cpp.)
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "frame_compare.h"
#include "generators/generators.h"
#include "gl_harness.h"
#include "slicing/frame_uniforms.h"
#include "slicing/renderer.h"
#include "slicing/slicer.h"
#include "slicing/technique_table.h"

namespace vsil {
namespace {

constexpr const char* kEveryEffect = "boundary,silhouette,fading,sketch,distance,halo,tone";

class TileMarch : public test::GlTest, public ::testing::WithParamInterface<std::string> {
 protected:
  // Renders `settings` with the fast and the tiles pipeline; every pixel must agree.
  void expectSameAsFast(const Volume& volume, RenderSettings settings) {
    settings.technique = GetParam();
    settings.options = test::isoOptions(findTechnique(GetParam()), 0.5);
    // illustrate: every effect at once, the halo field's fetches and the tone's lights included.
    if (GetParam() == "illustrate") settings.options["effects"] = std::string(kEveryEffect);
    Renderer renderer(test::sharedGlContext());
    renderer.setVolume(volume);
    settings.options["pipeline"] = std::string("fast");
    const RenderResult fast = renderer.render(settings);
    settings.options["pipeline"] = std::string("tiles");
    const RenderResult tiles = renderer.render(settings);
    if (GetParam() == "illustrate") {
      // The same samples composited in the same order, but a slice pass and a compute shader
      // round differently in the last bit (README "The default pipeline"): colours agree within
      // the 2/255 the CPU references allow for illustrate.
      EXPECT_LE(test::maxChannelDifference(fast.frame.color, tiles.frame.color), 2.0 / 255.0)
          << settings.size.x << "x" << settings.size.y << ", " << fast.sliceCount << " slices";
    } else {
      EXPECT_EQ(test::differingPixels(fast.frame, tiles.frame), 0)
          << settings.size.x << "x" << settings.size.y << ", " << fast.sliceCount << " slices";
    }
    shown_ = test::shownPixels(fast.frame);
  }
  int shown_ = 0;  // pixels the last frame showed
};

TEST_P(TileMarch, SlicesBeyondOneUniformBlockTakeSeveralDispatches) {
  const Volume volume = generateVolume("spheres:40");
  const int slicesPerDispatch = FrameUniforms().slicesPerRange();
  RenderSettings settings;
  settings.size = {72, 60};
  settings.camera.azimuthDeg = 50;
  const View view = makeView(settings.camera, volume.dims, volume.spacing, settings.size);
  // Enough slices for two dispatches and part of a third.
  const double perVoxel = double(planSlices(view, volume.dims, volume.spacing, 1.0).slices.size());
  settings.samplesPerVoxel = 2.5 * slicesPerDispatch / perVoxel;
  ASSERT_GT(planSlices(view, volume.dims, volume.spacing, settings.samplesPerVoxel).slices.size(),
            std::size_t(2 * slicesPerDispatch));
  expectSameAsFast(volume, settings);
  EXPECT_GT(shown_, 100) << "the comparison needs something to compare";
}

TEST_P(TileMarch, ImagesEndingInsideATileOrSmallerThanOne) {
  const Volume volume = generateVolume("torus:40");
  for (const glm::ivec2 size : {glm::ivec2(1, 1), glm::ivec2(2, 3), glm::ivec2(31, 29),
                                glm::ivec2(61, 33), glm::ivec2(200, 7), glm::ivec2(9, 130)}) {
    RenderSettings settings;
    settings.size = size;
    settings.camera.azimuthDeg = 20;
    settings.camera.elevationDeg = 35;
    expectSameAsFast(volume, settings);
  }
}

TEST_P(TileMarch, ViewsWhereTilesStartAndStopApart) {
  const Volume volume = generateVolume("blobs:48");
  for (const auto& [azimuth, elevation, orthographic, zoom] :
       {std::tuple{30.0, 20.0, false, 1.0}, std::tuple{135.0, -40.0, true, 1.4},
        std::tuple{0.0, 89.0, false, 2.5}, std::tuple{-70.0, 5.0, false, 0.7}}) {
    RenderSettings settings;
    settings.size = {97, 83};
    settings.camera.azimuthDeg = azimuth;
    settings.camera.elevationDeg = elevation;
    settings.camera.orthographic = orthographic;
    settings.camera.zoom = zoom;
    expectSameAsFast(volume, settings);
    EXPECT_GT(shown_, 100) << "the comparison needs something to compare";
  }
}

INSTANTIATE_TEST_SUITE_P(Techniques, TileMarch,
                         ::testing::Values("silhouette", "rightangle", "illustrate"),
                         [](const auto& info) { return info.param; });

}  // namespace
}  // namespace vsil
