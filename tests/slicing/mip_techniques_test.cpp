// mip, demip and lmip on volumes built here, whose structures and depths are known: what the
// paper's depth cues must show (Díaz & Vázquez), and LMIP's choice of the first local maximum.
// Pixel values are compared between structures of the same frame, never against goldens.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <random>
#include <span>

#include <gtest/gtest.h>

#include "analytic_volumes.h"
#include "gl_harness.h"
#include "reference_table.h"
#include "slicing/renderer.h"
#include "test_support.h"

namespace vsil {
namespace {

// Two balls of equal peak (1 on a plateau of radius 6), seen from +z (azimuth 0): `front` nearer
// the viewer than `back`, overlapping on screen between x = 26 and 38 only.
const test::Ball kFront{{24, 32, 44}, 10.0};
const test::Ball kBack{{40, 32, 20}, 10.0};

Volume twoBalls() {
  return test::ballsVolume({64, 64, 64}, {kFront, kBack});
}

// The pixel (top-left origin) that a voxel-space point projects to.
cv::Point pixelOf(const View& view, glm::dvec3 voxel) {
  const glm::dvec4 clip = view.clipFromVoxel() * glm::dvec4(voxel, 1.0);
  return {int((clip.x / clip.w + 1) * 0.5 * view.viewport.x),
          int((1 - clip.y / clip.w) * 0.5 * view.viewport.y)};
}

RenderSettings settingsFor(const std::string& technique, OptionValues options, double azimuth = 0) {
  RenderSettings settings;
  settings.technique = technique;
  settings.options = std::move(options);
  settings.size = {128, 128};
  settings.camera.orthographic = true;
  settings.camera.azimuthDeg = azimuth;
  settings.camera.elevationDeg = 0;
  return settings;
}

RenderResult renderTechnique(const Volume& volume, const std::string& technique,
                             OptionValues options, double azimuth = 0) {
  return test::renderOnce(volume, settingsFor(technique, std::move(options), azimuth));
}

float grey(const RenderResult& result, cv::Point pixel) {
  return result.frame.color(pixel)[0];
}

// Red minus blue of a pixel: > 0 toward the red end of a red-blue sphere.
float redOverBlue(const RenderResult& result, cv::Point pixel) {
  const cv::Vec4f c = result.frame.color(pixel);
  return c[0] - c[2];
}

using MipTechniques = test::GlTest;

TEST_F(MipTechniques, MipReadsEqualPeaksTheSameAtAnyDepth) {
  const RenderResult mip = renderTechnique(twoBalls(), "mip", {});
  const cv::Point front = pixelOf(mip.view, kFront.centreVoxel);
  const cv::Point back = pixelOf(mip.view, kBack.centreVoxel);
  // Trilinear samples of a plateau equal its value up to float rounding.
  EXPECT_NEAR(grey(mip, front), 1.0f, 1e-5);
  EXPECT_EQ(grey(mip, front), grey(mip, back));
}

TEST_F(MipTechniques, DemipBrightensTheFrontBallAndTheOverlapShowsItsDepth) {
  const Volume volume = twoBalls();
  // The window 0..2 keeps the peak's grey at 0.5, so that the depth term does not saturate.
  const RenderResult demip =
      renderTechnique(volume, "demip", {{"depth-weight", 0.3}, {"window", std::string("0,2")}});
  const cv::Point front = pixelOf(demip.view, kFront.centreVoxel);
  const cv::Point back = pixelOf(demip.view, kBack.centreVoxel);
  // Between the centres on screen both balls reach 0.75: the same maximum twice along the ray.
  const cv::Point overlap = pixelOf(demip.view, (kFront.centreVoxel + kBack.centreVoxel) * 0.5);
  const float frontDepth = demip.frame.depth(front), backDepth = demip.frame.depth(back);
  std::cout << "[ info ] depth front " << frontDepth << ", back " << backDepth << ", overlap "
            << demip.frame.depth(overlap) << "; grey front " << grey(demip, front) << ", back "
            << grey(demip, back) << "\n";
  // The first samples within eps = 0.05 of the peak: z = 50.4 and 26.4, 24 voxels apart in a
  // 64-voxel deep box.
  EXPECT_NEAR(backDepth - frontDepth, 24.0 / 64.0, 2.0 / 64.0);
  // color = 0.5·(1 − 0.3) + 2·0.3·(1 − depth): the front brighter by 0.6 times the depth gap.
  EXPECT_NEAR(grey(demip, front) - grey(demip, back), 0.6f * (backDepth - frontDepth), 1e-4);
  // There the first sample within eps = 0.05 of 0.75 lies in the front ball, 8 voxels off its
  // axis: f = 0.7 at r = 8.4, z = 44 + sqrt(8.4² − 8²) = 46.56, 3.84 voxels behind the front
  // ball's hit on its axis (z = 50.4, f = 0.95 at r = 6.4); the back ball's lies at z = 22.56.
  EXPECT_NEAR(demip.frame.depth(overlap), frontDepth + 3.84 / 64.0, 2.0 / 64.0);
  EXPECT_GT(grey(demip, overlap), 0.0f);
}

TEST_F(MipTechniques, RedBlueSphereMarksFrontRedAndRotationSwapsIt) {
  const Volume volume = twoBalls();
  const OptionValues sphere = {{"sphere-weight", 1.0}, {"sphere-map", std::string("red-blue")}};
  const RenderResult plain = renderTechnique(volume, "demip", sphere);
  const cv::Point front = pixelOf(plain.view, kFront.centreVoxel);
  const cv::Point back = pixelOf(plain.view, kBack.centreVoxel);
  // Front hit (24, 32, 50): 18.5 voxels toward the viewer from the centre (31.5, 31.5, 31.5);
  // back hit (40, 32, 26): 5.5 away.
  EXPECT_GT(redOverBlue(plain, front), 0.5f);
  EXPECT_LT(redOverBlue(plain, back), -0.3f);
  OptionValues rotated = sphere;
  rotated["sphere-rotate"] = std::string("180,0");
  const RenderResult turned = renderTechnique(volume, "demip", rotated);
  EXPECT_NEAR(redOverBlue(turned, front), -redOverBlue(plain, front), 1e-5);
  EXPECT_NEAR(redOverBlue(turned, back), -redOverBlue(plain, back), 1e-5);
}

TEST_F(MipTechniques, VolumeFrameKeepsAStructuresColourWhileTheViewOrbits) {
  const Volume volume = twoBalls();
  OptionValues options = {{"sphere-weight", 1.0}, {"sphere-frame", std::string("volume")}};
  // From behind (azimuth 180) the front ball is the far one. Fixed to the volume, its colour
  // stays red; fixed to the view, it turns blue.
  const RenderResult fromFront = renderTechnique(volume, "demip", options, 0);
  const RenderResult fromBehind = renderTechnique(volume, "demip", options, 180);
  options["sphere-frame"] = std::string("view");
  const RenderResult viewFrame = renderTechnique(volume, "demip", options, 180);
  const cv::Point frontBall0 = pixelOf(fromFront.view, kFront.centreVoxel);
  const cv::Point frontBall180 = pixelOf(fromBehind.view, kFront.centreVoxel);
  EXPECT_GT(redOverBlue(fromFront, frontBall0), 0.3f);
  EXPECT_GT(redOverBlue(fromBehind, frontBall180), 0.1f);
  EXPECT_LT(redOverBlue(viewFrame, frontBall180), -0.1f);
}

TEST_F(MipTechniques, LegendShowsTheSphereAsUsedInTheCorner) {
  const Volume volume = twoBalls();
  OptionValues options = {{"legend", true}};
  const RenderResult plain = renderTechnique(volume, "demip", options);
  options["sphere-rotate"] = std::string("180,0");
  const RenderResult turned = renderTechnique(volume, "demip", options);
  // The inset's centre is the view direction (a white cross); beside it, toward the viewer:
  // red unturned, blue turned.
  const int radius = 128 / 10, margin = radius / 4;
  const cv::Point centre(128 - margin - radius - 1, 128 - margin - radius - 1);
  EXPECT_EQ(plain.frame.color(centre), cv::Vec4f(1, 1, 1, 1));
  const cv::Point nearCentre = centre + cv::Point(radius / 2, radius / 2);
  EXPECT_GT(redOverBlue(plain, nearCentre), 0.5f);
  EXPECT_LT(redOverBlue(turned, nearCentre), -0.5f);
  // Outside the disc the frame is untouched: the corner pixel shows the empty background.
  EXPECT_EQ(plain.frame.color(127, 127)[3], 0.0f);
}

// A weak ball (peak 0.5) in front of a strong one (peak 1), one behind the other on screen.
Volume weakFrontStrongBack() {
  const test::Ball weak{{32, 32, 44}, 10.0}, strong{{32, 32, 20}, 10.0};
  const Volume front = test::ballsVolume({64, 64, 64}, {weak});
  Volume volume = test::ballsVolume({64, 64, 64}, {strong});
  const std::span<const float> frontSamples = front.samples<float>();
  const std::span<float> samples = volume.samples<float>();
  for (std::size_t i = 0; i < samples.size(); ++i) {
    samples[i] = std::max(samples[i], 0.5f * frontSamples[i]);
  }
  return volume;
}

TEST_F(MipTechniques, LmipShowsTheWeakFrontBallUntilTheThresholdPassesIt) {
  const Volume volume = weakFrontStrongBack();
  const std::string window = "0,1";
  const RenderResult low =
      renderTechnique(volume, "lmip", {{"lmip-threshold", 0.3}, {"window", window}});
  const RenderResult high =
      renderTechnique(volume, "lmip", {{"lmip-threshold", 0.7}, {"window", window}});
  const RenderResult mip = renderTechnique(volume, "mip", {{"window", window}});
  const cv::Point centre = pixelOf(low.view, {32, 32, 32});
  // Trilinear samples of a plateau equal its value up to float rounding.
  EXPECT_NEAR(grey(low, centre), 0.5f, 1e-5) << "the weak ball's peak";
  EXPECT_NEAR(grey(high, centre), 1.0f, 1e-5) << "the strong ball's peak";
  EXPECT_NEAR(grey(mip, centre), 1.0f, 1e-5);
  // The local maximum's depth: the weak ball's plateau (near face z = 50), the strong one's (26).
  EXPECT_NEAR(high.frame.depth(centre) - low.frame.depth(centre), 24.0 / 64.0, 2.0 / 64.0);
}

// --tf: a pixel's value takes the transfer function's colour and opacity. This one is
// transparent up to 0.55, then red turning yellow at 1: of weakFrontStrongBack (peaks 0.5 and
// 1), the weak ball's peak is transparent and the strong one's yellow. GL agrees with the CPU
// reference for all three techniques (the table read with GL's linear filtering: within
// 2/255, as illustrate's transfer function), and skipping bricks changes no byte.
TEST_F(MipTechniques, TransferFunctionColoursTheValueAndMatchesTheReference) {
  const std::string tf = (test::scratchDir() / "tf.json").string();
  std::ofstream(tf) << R"([{"value": 0, "color": "#000000", "opacity": 0},
                          {"value": 0.55, "color": "#ff0000", "opacity": 0},
                          {"value": 0.6, "color": "#ff0000", "opacity": 0.5},
                          {"value": 1, "color": "#ffff00", "opacity": 1}])";
  const Volume volume = weakFrontStrongBack();
  const std::vector<std::pair<std::string, OptionValues>> cases{
      {"mip", {{"tf", tf}}},
      {"lmip", {{"tf", tf}, {"lmip-threshold", 0.3}}},
      {"demip", {{"tf", tf}, {"sphere-weight", 0.3}}},
  };
  for (const auto& [technique, options] : cases) {
    SCOPED_TRACE(technique);
    RenderSettings settings = settingsFor(technique, options);
    const RenderResult gl = test::renderOnce(volume, settings);
    const reference::ReferenceFrame cpu =
        reference::findReference(technique).render(volume, settings, 1e-4f);
    int shown = 0, differing = 0;
    float maxError = 0;
    for (int y = 0; y < settings.size.y; ++y) {
      for (int x = 0; x < settings.size.x; ++x) {
        shown += cpu.frame.color(y, x)[3] > 0;
        if (cpu.ambiguous(y, x)) continue;
        float error = 0;
        for (int k = 0; k < 4; ++k) {
          error = std::max(error, std::abs(gl.frame.color(y, x)[k] - cpu.frame.color(y, x)[k]));
        }
        maxError = std::max(maxError, error);
        differing += error > 2.0f / 255;
      }
    }
    // The strong ball's disc beyond the 0.55 shell (about 380 pixels); for lmip only its rim,
    // where the weak ball's transparent peak does not lie in front.
    EXPECT_GT(shown, technique == "lmip" ? 10 : 300);
    EXPECT_EQ(differing, 0) << "max error " << maxError * 255 << "/255";

    settings.emptySpaceSkipping = false;
    const RenderResult unskipped = test::renderOnce(volume, settings);
    EXPECT_EQ(cv::norm(gl.frame.color, unskipped.frame.color, cv::NORM_INF), 0.0);
  }
  const cv::Point centre = pixelOf(renderTechnique(volume, "mip", {}).view, {32, 32, 32});
  const cv::Vec4f strong = renderTechnique(volume, "mip", {{"tf", tf}}).frame.color(centre);
  EXPECT_NEAR(strong[0], 1.0f, 2.0f / 255) << "yellow, opacity 1";
  EXPECT_NEAR(strong[1], 1.0f, 2.0f / 255);
  EXPECT_NEAR(strong[2], 0.0f, 2.0f / 255);
  EXPECT_NEAR(strong[3], 1.0f, 2.0f / 255);
  const cv::Vec4f weak =
      renderTechnique(volume, "lmip", {{"tf", tf}, {"lmip-threshold", 0.3}}).frame.color(centre);
  EXPECT_EQ(weak[3], 0.0f) << "lmip's first local maximum, 0.5, is transparent";
}

// Noise over steps along z, some rising by more than material-eps at once, some by less: both
// ways a ray's maximum can grow (max_march.comp's bound on the first hit).
Volume noisySteps() {
  Volume volume;
  volume.name = "noisy steps";
  volume.source = "test:noisy-steps";
  volume.dims = {40, 36, 44};
  volume.allocate(SampleType::Float32);
  const std::span<float> samples = volume.samples<float>();
  std::mt19937 random(7);
  std::uniform_real_distribution<float> noise(0.0f, 0.3f);
  for (int z = 0; z < volume.dims.z; ++z) {
    for (int y = 0; y < volume.dims.y; ++y) {
      for (int x = 0; x < volume.dims.x; ++x) {
        const float step = float((z + x / 8) % 11) * 0.07f;
        samples[volume.index(x, y, z)] = step + noise(random);
      }
    }
  }
  return volume;
}

// With the volume in one texture mip and demip march (max_march.comp); in bricks they draw
// passes per slice (max_sample.frag, first_hit.frag). Both sample the same positions and must
// leave the same bytes, the first hit included, for any material-eps.
TEST_F(MipTechniques, MarchAndSlicePassesLeaveTheSameBytes) {
  const Volume volume = noisySteps();
  Renderer whole(test::sharedGlContext()), bricked(test::sharedGlContext());
  whole.setVolume(volume);
  bricked.setVolume(volume, 16 * 16 * 16 * 4);  // bricks of 16³ R32F texels
  ASSERT_EQ(whole.brickCount(), 1u);
  ASSERT_GT(bricked.brickCount(), 8u);
  const std::vector<std::pair<std::string, OptionValues>> cases{
      {"mip", {}},
      {"demip", {}},
      {"demip", {{"material-eps", 0.01}, {"depth-weight", 0.5}}},
      {"demip", {{"material-eps", 0.2}, {"sphere-weight", 0.4}}},
      {"demip", {{"material-eps", 5.0}}},
  };
  for (const bool orthographic : {false, true}) {
    for (const auto& [technique, options] : cases) {
      RenderSettings settings = settingsFor(technique, options, orthographic ? 17 : -33);
      settings.camera.orthographic = orthographic;
      settings.camera.elevationDeg = 21;
      settings.samplesPerVoxel = 1.3;
      SCOPED_TRACE(
          technique + (orthographic ? ", orthographic" : ", perspective") +
          (options.count("material-eps")
               ? ", material-eps " + std::to_string(std::get<double>(options.at("material-eps")))
               : ""));
      const RenderResult marched = whole.render(settings);
      const RenderResult sliced = bricked.render(settings);
      EXPECT_EQ(cv::norm(marched.frame.color, sliced.frame.color, cv::NORM_INF), 0.0);
      if (technique == "demip") {
        ASSERT_FALSE(marched.frame.depth.empty());
        int differing = 0, hits = 0;
        for (int y = 0; y < settings.size.y; ++y) {
          for (int x = 0; x < settings.size.x; ++x) {
            const float a = marched.frame.depth(y, x), b = sliced.frame.depth(y, x);
            hits += !std::isnan(a);
            differing += !(a == b || (std::isnan(a) && std::isnan(b)));
          }
        }
        EXPECT_EQ(differing, 0);
        EXPECT_GT(hits, 2000);
      }
    }
  }
}

// RenderSettings::readDepth off (`vsil render` without --depth-out): the same colour, no depth.
TEST_F(MipTechniques, DepthIsReadBackOnlyWhenAsked) {
  const Volume volume = twoBalls();
  Renderer renderer(test::sharedGlContext());
  renderer.setVolume(volume);
  const std::vector<std::pair<std::string, OptionValues>> cases{
      {"demip", {{"depth-weight", 0.3}}},
      {"demip", {{"sphere-weight", 0.5}, {"legend", true}}},
      {"lmip", {{"lmip-threshold", 0.5}}},
  };
  for (const auto& [technique, options] : cases) {
    SCOPED_TRACE(technique);
    RenderSettings settings = settingsFor(technique, options, 30);
    const RenderResult withDepth = renderer.render(settings);
    settings.readDepth = false;
    const RenderResult colourOnly = renderer.render(settings);
    ASSERT_FALSE(withDepth.frame.depth.empty());
    EXPECT_GT(cv::countNonZero(withDepth.frame.depth == withDepth.frame.depth), 500);
    EXPECT_TRUE(colourOnly.frame.depth.empty());
    EXPECT_EQ(cv::norm(withDepth.frame.color, colourOnly.frame.color, cv::NORM_INF), 0.0);
  }
}

}  // namespace
}  // namespace vsil
