// `--fill tone` (slicing/tone_fill.h) on analytic spheres: what tone shading and distance
// blending must do to the Filled pixels, and that asking for it changes nothing else. The
// comparison with the CPU reference is in gl_vs_reference_test.cpp (every scene and pipeline of
// silhouette and rightangle tone-fills).
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "frame_compare.h"
#include "generators/generators.h"
#include "gl_harness.h"
#include "slicing/renderer.h"

namespace vsil {
namespace {

RenderSettings sphereSettings(const std::string& technique) {
  RenderSettings settings;
  settings.technique = technique;
  settings.size = {96, 96};
  settings.options["iso"] = 0.5;
  settings.camera.orthographic = true;
  settings.camera.zoom = 2.0;
  return settings;
}

// Mean (r + g)/2 − b of the tone colours of the Filled pixels above (`upper`) or below the
// middle third of the Filled disc: how warm (yellow) rather than cool (blue) that side is.
double toneWarmth(const FrameBuffers& frame, bool upper) {
  double rows = 0, count = 0, top = frame.height(), bottom = 0;
  for (int y = 0; y < frame.height(); ++y) {
    for (int x = 0; x < frame.width(); ++x) {
      if (PixelState(frame.state(y, x)) != PixelState::Filled) continue;
      rows += y;
      ++count;
      top = std::min<double>(top, y);
      bottom = std::max<double>(bottom, y);
    }
  }
  const double middle = rows / count, third = (bottom - top) / 6.0;
  double sum = 0;
  int used = 0;
  for (int y = 0; y < frame.height(); ++y) {
    const bool side = upper ? y < middle - third : y > middle + third;
    if (!side) continue;
    for (int x = 0; x < frame.width(); ++x) {
      if (PixelState(frame.state(y, x)) != PixelState::Filled) continue;
      const cv::Vec3f& c = frame.tone(y, x);
      sum += (c[0] + c[1]) / 2 - c[2];
      ++used;
    }
  }
  EXPECT_GT(used, 50) << "the side should hold part of the sphere";
  return used ? sum / used : 0;
}

class ToneFill : public test::GlTest, public ::testing::WithParamInterface<std::string> {};

TEST_P(ToneFill, TheSideLitFromAboveIsWarmAndTheFarSideCool) {
  const Volume volume = generateVolume("sphere:48");
  RenderSettings settings = sphereSettings(GetParam());
  settings.toneFill = Rgba{96, 96, 96, 255};  // a grey that leaves room below white
  settings.options["light"] = std::vector<std::string>{"0,90"};  // straight above
  const RenderResult result = test::renderOnce(volume, settings);
  ASSERT_FALSE(result.frame.tone.empty());
  const double top = toneWarmth(result.frame, true), bottom = toneWarmth(result.frame, false);
  std::cout << "[ info ] warmth (r + g)/2 - b: top " << top << ", bottom " << bottom << "\n";
  // Illustrate's defaults: the grey terms (I_G, k_td·c_o·max(n·L, 0)) cancel in (r + g)/2 − b;
  // the top gains k_ty·t − k_tb·(1 − t) ≈ 0.3·0.9 − 0.3·0.1 of yellow, the bottom as much of
  // blue (distance blending is off by default: tone_fill.h), all divided by the sum's peak
  // 1.9 (toneShadingPeak): up to ±0.16 where n·L is largest, ±0.095 on average over a side.
  EXPECT_GT(top, 0.06) << "the lit side is yellow";
  EXPECT_LT(bottom, -0.06) << "the far side is blue";
  EXPECT_GT(top, bottom + 0.15);
}

// Lit side warm, far side cool, the highlight not clipped (frame_compare.h).
TEST_P(ToneFill, IvoryIsWarmWhereLitCoolWhereNotAndNotClipped) {
  RenderSettings settings = sphereSettings(GetParam());
  settings.toneFill = Rgba{255, 255, 240, 255};  // ivory
  test::expectIvoryToneWarmWhereLitCoolWhereNotAndNotClipped(generateVolume("sphere:48"), settings);
}

TEST_P(ToneFill, WithoutTheToneTermsTheFillIsTheBackgroundBlendedByDepth) {
  // k_ta = k_td = k_ty = k_tb = 0 leaves I = 0; k_ds = k_de = 1 then gives c = d·c_b.
  const Volume volume = generateVolume("sphere:48");
  RenderSettings settings = sphereSettings(GetParam());
  settings.toneFill = Rgba{200, 200, 200, 255};
  settings.background = Rgba{255, 0, 0, 255};
  settings.options["param"] =
      std::vector<std::string>{"k_ta=0,k_td=0,k_ty=0,k_tb=0", "k_ds=1,k_de=1"};
  const RenderResult result = test::renderOnce(volume, settings);
  ASSERT_FALSE(result.frame.tone.empty());
  int filled = 0;
  double largest = 0;
  for (int y = 0; y < result.frame.height(); ++y) {
    for (int x = 0; x < result.frame.width(); ++x) {
      const cv::Vec3f& c = result.frame.tone(y, x);
      if (PixelState(result.frame.state(y, x)) != PixelState::Filled) {
        EXPECT_TRUE(std::isnan(c[0])) << "(" << x << "," << y << ") is not Filled";
        continue;
      }
      ++filled;
      const double d = result.frame.depth(y, x);
      largest =
          std::max({largest, std::abs(c[0] - d), double(std::abs(c[1])), double(std::abs(c[2]))});
    }
  }
  EXPECT_GT(filled, 1000);
  // pow(d, 1) through llvmpipe's exp2/log2: a few float ulps.
  EXPECT_LT(largest, 1e-5);
}

TEST_P(ToneFill, AskingForItChangesNoStateDepthOrShade) {
  const Volume volume = generateVolume("torus:48");
  RenderSettings settings = sphereSettings(GetParam());
  settings.camera.orthographic = false;
  settings.camera.elevationDeg = 40;
  const RenderResult plain = test::renderOnce(volume, settings);
  EXPECT_TRUE(plain.frame.tone.empty()) << "no tone fill asked for";
  settings.toneFill = Rgba{96, 96, 96, 255};
  RenderResult toned = test::renderOnce(volume, settings);
  ASSERT_FALSE(toned.frame.tone.empty());
  toned.frame.tone.release();
  EXPECT_EQ(test::differingPixels(plain.frame, toned.frame), 0);
  EXPECT_TRUE(toned.options.contains("tone_fill"));
  EXPECT_FALSE(plain.options.contains("tone_fill"));
}

INSTANTIATE_TEST_SUITE_P(StateTechniques, ToneFill, ::testing::Values("silhouette", "rightangle"),
                         [](const auto& info) { return info.param; });

}  // namespace
}  // namespace vsil
