// The illustrate technique (slicing/techniques/illustrate/): each effect alone and all together
// against the CPU reference (tests/reference/illustrate_reference.h), neutral parameters against
// the plain composite, and what each effect must do to an analytic shape (the issue's list).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <random>
#include <span>
#include <sstream>
#include <string>
#include <tuple>

#include <gtest/gtest.h>

#include "analytic_volumes.h"
#include "frame_compare.h"
#include "generators/generators.h"
#include "gl_harness.h"
#include "illustrate_reference.h"
#include "slicing/renderer.h"
#include "slicing/techniques/illustrate/halo_mask.h"

namespace vsil {
namespace {

struct EffectCase {
  std::string name;
  std::string effects;
  std::string params;  // --param, "" for the defaults
  bool transferFunction = false;
};

std::ostream& operator<<(std::ostream& out, const EffectCase& c) {
  return out << c.name;
}

// A transfer function over gen:sphere's values (0 .. ~1) times `scale`: transparent outside, a
// reddish shell, an opaque ivory core.
std::string sphereTransferFunction(double scale = 1.0) {
  const auto file =
      std::filesystem::temp_directory_path() / ("vsil_illustrate_tf_" + std::to_string(::getpid()) +
                                                "_" + std::to_string(int(scale)) + ".json");
  std::ofstream(file) << "[{\"value\": " << 0.05 * scale << R"(, "color": "#000000", "opacity": 0},
      {"value": )" << 0.3 * scale
                      << R"(, "color": "#c06040", "opacity": 0.05},
      {"value": )" << 0.6 * scale
                      << R"(, "color": "#fffff0", "opacity": 0.3}])";
  return file.string();
}

// gen:sphere in 8 bits, round(255·f): small integers, so the volume texture is R16F and the
// gradient texture holds the values too (gradient_texture.h), the path the classic datasets take;
// gen:sphere itself takes the other (R32F, values sampled from the volume texture).
Volume eightBitSphere() {
  const Volume sphere = generateVolume("sphere:48");
  Volume volume;
  volume.dims = sphere.dims;
  volume.allocate(SampleType::UInt8);
  std::span<std::uint8_t> samples = volume.samples<std::uint8_t>();
  for (std::size_t i = 0; i < samples.size(); ++i) {
    samples[i] = std::uint8_t(std::lround(255.0 * sphere.value(i)));
  }
  return volume;
}

RenderSettings illustrateSettings(const std::string& effects, const std::string& params,
                                  glm::ivec2 size = {96, 80}) {
  RenderSettings settings;
  settings.technique = "illustrate";
  if (!effects.empty()) settings.options["effects"] = effects;
  if (!params.empty()) settings.options["param"] = std::vector<std::string>{params};
  settings.size = size;
  settings.camera.azimuthDeg = 30;
  settings.camera.elevationDeg = 20;
  settings.camera.zoom = 1.4;
  return settings;
}

// Low opacity (k_os 0.3) keeps every ray from saturating, so each sample's contribution shows.
const EffectCase kEffectCases[] = {
    {"plain", "", "k_os=0.3"},
    {"boundary", "boundary", "k_os=0.3"},
    {"silhouette", "silhouette", "k_os=0.3"},
    {"fading", "fading", "k_os=0.3,k_fo=0.5"},
    {"sketch", "sketch", "k_os=0.3"},
    {"distance", "distance", "k_os=0.3"},
    {"halo", "halo", "k_os=0.3"},
    {"tone", "tone", "k_os=0.3"},
    {"all", "boundary,silhouette,fading,sketch,distance,halo,tone", "k_os=0.3"},
    {"all_but_sketch_two_lights", "boundary,silhouette,fading,distance,halo,tone", "k_os=0.3"},
    {"transfer_function_all", "boundary,silhouette,fading,distance,halo,tone", "", true},
};

class IllustrateMatchesReference
    : public test::GlTest,
      public ::testing::WithParamInterface<std::tuple<EffectCase, bool>> {};

TEST_P(IllustrateMatchesReference, EveryChannelWithin2Of255) {
  const auto& [c, eightBit] = GetParam();
  const Volume volume = eightBit ? eightBitSphere() : generateVolume("sphere:48");
  RenderSettings settings = illustrateSettings(c.effects, c.params);
  if (c.transferFunction) settings.options["tf"] = sphereTransferFunction(eightBit ? 255 : 1);
  if (c.name == "all_but_sketch_two_lights") {
    settings.options["light"] = std::vector<std::string>{"0,60", "-70,10"};
  }
  settings.background = Rgba{20, 30, 90, 255};  // distance blending's c_b, not white
  const reference::ReferenceFrame cpu = reference::renderIllustrate(volume, settings, 0.0f);
  Renderer renderer(test::sharedGlContext());
  renderer.setVolume(volume);
  const RenderResult gl = renderer.render(settings);
  ASSERT_EQ(gl.sliceCount, cpu.sliceCount);
  double maxError = 0;
  int over = 0, ambiguous = 0;
  std::ostringstream first;
  for (int y = 0; y < settings.size.y; ++y) {
    for (int x = 0; x < settings.size.x; ++x) {
      const double pixelError = test::maxChannelDifference(gl.frame.color, cpu.frame.color, y, x);
      // The box-aligned samples' phase within rounding of 0 or 1 (slice_sampler.h): GL may
      // sample one slice over, with distance blending's depths a step apart.
      if (cpu.ambiguous(y, x)) {
        ambiguous += pixelError > 2.0 / 255.0;
        continue;
      }
      maxError = std::max(maxError, pixelError);
      if (pixelError > 2.0 / 255.0 && ++over <= 3) {
        first << " (" << x << "," << y << ") gl " << gl.frame.color(y, x) << " cpu "
              << cpu.frame.color(y, x) << ";";
      }
    }
  }
  const int shown = test::shownPixels(cpu.frame);
  std::cout << "[ info ] " << c.name << (eightBit ? " (8-bit)" : "") << ": " << shown
            << " pixels shown, max channel error " << maxError * 255.0 << "/255, " << over
            << " pixels over 2/255, " << ambiguous << " ambiguous pixels differing\n";
  EXPECT_GT(shown, 500);
  // Both composite in float; 2/255 covers early ray termination (<= 1/255) and trilinear weights
  // rounded differently, and is far below what a wrong formula or sample position changes.
  // Halo taps read the nearest texel: a tap within float rounding of a texel border may read
  // the neighbour in GL, so with halos a few pixels (at most 0.2 % of those shown) may differ
  // more, never by more than 8/255.
  const bool halos = c.effects.find("halo") != std::string::npos;
  EXPECT_LE(over, halos ? shown / 500 : 0) << "pixels off by more than 2/255:" << first.str();
  EXPECT_LE(maxError, (halos ? 8.0 : 2.0) / 255.0) << first.str();
  EXPECT_LE(ambiguous, std::max(2, shown / 100));
}

INSTANTIATE_TEST_SUITE_P(Effects, IllustrateMatchesReference,
                         ::testing::Combine(::testing::ValuesIn(kEffectCases), ::testing::Bool()),
                         [](const auto& info) {
                           return std::get<0>(info.param).name +
                                  (std::get<1>(info.param) ? "_8bit" : "");
                         });

using IllustrateTest = test::GlTest;

TEST_F(IllustrateTest, NeutralParametersGiveExactlyThePlainComposite) {
  const Volume volume = generateVolume("sphere:48");
  const RenderResult plain = test::renderOnce(volume, illustrateSettings("", "k_os=0.3"));
  // Every effect but sketch (which has no neutral setting: it replaces the colour).
  const RenderResult neutral = test::renderOnce(
      volume, illustrateSettings("boundary,silhouette,fading,distance,halo,tone",
                                 "k_os=0.3,k_gc=1,k_gs=0,k_sc=1,k_ss=0,k_fs=0,k_fv=0,k_fo=0,"
                                 "k_ds=0,k_hd=0,k_ho=0,k_ta=1,k_td=0,k_ty=0,k_tb=0"));
  EXPECT_GT(test::shownPixels(plain.frame), 500);
  EXPECT_EQ(test::differingPixels(plain.frame, neutral.frame), 0)
      << "max channel difference "
      << test::maxChannelDifference(plain.frame.color, neutral.frame.color);
}

// Mean over a block of straight colours (premultiplied divided by alpha) of (r + g)/2 − b: how
// warm (yellow) rather than cool (blue) it looks.
double warmth(const cv::Mat4f& color, cv::Rect block) {
  double sum = 0;
  int count = 0;
  for (int y = block.y; y < block.y + block.height; ++y) {
    for (int x = block.x; x < block.x + block.width; ++x) {
      const cv::Vec4f c = color(y, x);
      if (c[3] < 0.05f) continue;
      sum += ((c[0] + c[1]) / 2 - c[2]) / c[3];
      ++count;
    }
  }
  EXPECT_GT(count, 10) << "the block should hold the sphere";
  return count ? sum / count : 0;
}

TEST_F(IllustrateTest, ToneShadingMakesTheLitSideWarmerAndTheFarSideCooler) {
  const Volume volume = generateVolume("sphere:48");
  RenderSettings settings = illustrateSettings("tone", "k_os=2", {80, 80});
  // A grey that leaves room: ivory lit from above plus the warm tone clamps to white.
  settings.options["color"] = std::string("#606060");
  settings.camera.azimuthDeg = 0;
  settings.camera.elevationDeg = 0;
  settings.options["light"] = std::vector<std::string>{"0,90"};  // straight above
  const RenderResult toned = test::renderOnce(volume, settings);
  settings.options.erase("effects");
  const RenderResult plain = test::renderOnce(volume, settings);
  const cv::Rect top(30, 14, 20, 10), bottom(30, 56, 20, 10);  // rows top-down
  const double topWarmth = warmth(toned.frame.color, top);
  const double bottomWarmth = warmth(toned.frame.color, bottom);
  std::cout << "[ info ] warmth top " << topWarmth << ", bottom " << bottomWarmth << "; plain "
            << warmth(plain.frame.color, top) << ", " << warmth(plain.frame.color, bottom) << "\n";
  EXPECT_GT(topWarmth, bottomWarmth + 0.1);
  // Against the plain ivory composite: the top gains yellow, the bottom gains blue.
  EXPECT_GT(topWarmth, warmth(plain.frame.color, top));
  EXPECT_LT(bottomWarmth, warmth(plain.frame.color, bottom));
}

TEST_F(IllustrateTest, SilhouetteEnhancementRaisesOpacityAtTheRimNotWhereTheSphereFacesTheViewer) {
  // A ball whose inside is flat (no gradient: counts as facing the viewer); gen:sphere's cone
  // has an apex whose interpolated normals point anywhere.
  const Volume volume = test::ballsVolume({64, 64, 64}, {{{31.5, 31.5, 31.5}, 20.0}}, 8.0);
  // k_se = 1: with the paper's 0.25, (1 − |n·v|)^k_se reaches 0.1 already at |n·v| = 0.9999,
  // so the trilinear normals' rounding along the centre ray would enhance it too.
  RenderSettings settings = illustrateSettings("silhouette", "k_os=0.05,k_se=1", {96, 96});
  settings.camera.orthographic = true;
  settings.camera.azimuthDeg = 0;
  settings.camera.elevationDeg = 0;
  const RenderResult enhanced = test::renderOnce(volume, settings);
  settings.options.erase("effects");
  const RenderResult plain = test::renderOnce(volume, settings);
  const auto alphaRatio = [&](int x, int y) {
    return enhanced.frame.color(y, x)[3] / std::max(plain.frame.color(y, x)[3], 1e-6f);
  };
  // The centre's ray meets normals along the view (|n·v| ≈ 1): o·k_sc, no more. Find the rim:
  // the outermost pixel of the centre row the plain composite shows.
  const int y = 48;
  int rim = 48;
  while (rim + 1 < 96 && plain.frame.color(y, rim + 1)[3] > 1e-3f) ++rim;
  ASSERT_GT(rim, 60);
  std::cout << "[ info ] alpha ratio centre " << alphaRatio(48, y) << ", rim (x " << rim - 1 << ") "
            << alphaRatio(rim - 1, y) << "\n";
  EXPECT_LE(alphaRatio(48, y), 1.0f);
  EXPECT_GT(alphaRatio(rim - 1, y), 2.0f);
}

TEST_F(IllustrateTest, HalosDarkenJustOutsideTheOutlineAndChangeNothingInside) {
  // A ball with a sharp boundary (ramp 2 voxels) in front of the white background.
  const Volume volume = test::ballsVolume({48, 48, 48}, {{{23.5, 23.5, 23.5}, 12.0}}, 2.0);
  RenderSettings settings = illustrateSettings("halo", "k_os=1,k_hr=4", {96, 96});
  settings.camera.orthographic = true;
  settings.camera.azimuthDeg = 0;
  settings.camera.elevationDeg = 0;
  const RenderResult halo = test::renderOnce(volume, settings);
  settings.options.erase("effects");
  const RenderResult plain = test::renderOnce(volume, settings);
  const int y = 48;
  int edge = 48;  // the outermost pixel of the centre row the plain ball covers
  while (edge + 1 < 96 && plain.frame.color(y, edge + 1)[3] > 1e-3f) ++edge;
  ASSERT_GT(edge, 60);
  ASSERT_LT(edge, 90);
  // Just outside: the halo adds opacity (dark over white). Two pixels out, still in the radius.
  const float outsideAlpha = halo.frame.color(y, edge + 2)[3];
  std::cout << "[ info ] edge x " << edge << ": alpha outside " << outsideAlpha << " (plain "
            << plain.frame.color(y, edge + 2)[3] << ")\n";
  EXPECT_GT(outsideAlpha, plain.frame.color(y, edge + 2)[3] + 0.05f);
  // Composed over white, darker there.
  const cv::Vec4f h = halo.frame.color(y, edge + 2);
  EXPECT_LT(h[0] + (1 - h[3]), 1.0f - 0.05f) << "the halo should darken the background";
  // Inside, around the centre: nothing changes (the neighbours' normals point away from it);
  // 1e-5 allows float rounding in the halo program's different instruction order.
  for (int x = 40; x <= 56; ++x) {
    for (int k = 0; k < 4; ++k) {
      EXPECT_NEAR(halo.frame.color(y, x)[k], plain.frame.color(y, x)[k], 1e-5) << "x " << x;
    }
  }
}

TEST(HaloMask, MarksExactlyTheVoxelsWithinTheRadiusOfAVisibleOne) {
  // Against the definition, voxel by voxel: a few visible voxels (value > 0.5) in a volume of
  // odd dims, every radius kind (below one voxel, whole, between whole numbers).
  const glm::ivec3 dims(23, 17, 13);
  std::vector<float> samples(std::size_t(dims.x) * dims.y * dims.z, 0.0f);
  std::vector<glm::ivec3> visible{{0, 0, 0}, {22, 16, 12}, {11, 8, 6}};
  std::mt19937 random(9);
  for (int i = 0; i < 4; ++i) {
    visible.push_back({int(random() % 23), int(random() % 17), int(random() % 13)});
  }
  for (const glm::ivec3& v : visible) {
    samples[(std::size_t(v.z) * dims.y + v.y) * dims.x + v.x] = 1.0f;
  }
  for (const double radius : {0.5, 1.0, 1.5, 2.9, 4.0, 6.5, 32.0}) {
    const std::vector<std::uint8_t> mask = haloMaskVoxels(
        samples.data(), dims, [](float value) { return value > 0.5f; }, radius);
    int marked = 0;
    for (int z = 0; z < dims.z; ++z) {
      for (int y = 0; y < dims.y; ++y) {
        for (int x = 0; x < dims.x; ++x) {
          const bool near = std::any_of(visible.begin(), visible.end(), [&](glm::ivec3 v) {
            const glm::ivec3 d = v - glm::ivec3(x, y, z);
            return double(d.x * d.x + d.y * d.y + d.z * d.z) <= radius * radius;
          });
          const bool inMask = mask[(std::size_t(z) * dims.y + y) * dims.x + x] != 0;
          ASSERT_EQ(inMask, near) << "radius " << radius << " voxel " << x << "," << y << "," << z;
          marked += inMask;
        }
      }
    }
    EXPECT_GE(marked, 7);
  }
}

TEST_F(IllustrateTest, DistanceBlendingMovesSamplesTowardTheBackgroundMonotonicallyWithDepth) {
  const Volume volume = generateVolume("sphere:64");
  RenderSettings settings = illustrateSettings("distance", "k_os=4,k_de=1", {96, 96});
  settings.camera.orthographic = true;
  settings.camera.azimuthDeg = 0;
  settings.camera.elevationDeg = 0;
  settings.background = Rgba{0, 0, 0, 255};  // c_b black: blending darkens
  const RenderResult blended = test::renderOnce(volume, settings);
  settings.options.erase("effects");
  const RenderResult plain = test::renderOnce(volume, settings);
  // Along the centre row the front surface lies deeper the farther from the centre: the share
  // of colour kept falls monotonically, from the centre out to the rim.
  const int y = 48;
  float previous = 2.0f;
  int checked = 0;
  for (int x = 48; x < 96 && plain.frame.color(y, x)[3] > 0.5f; ++x) {
    const float kept = blended.frame.color(y, x)[1] / plain.frame.color(y, x)[1];
    EXPECT_LE(kept, previous + 1e-3f) << "x " << x;
    EXPECT_LT(kept, 1.0f) << "x " << x;
    previous = kept;
    ++checked;
  }
  EXPECT_GT(checked, 10);
  EXPECT_LT(previous, blended.frame.color(y, 48)[1] / plain.frame.color(y, 48)[1] - 0.02f);
}

TEST_F(IllustrateTest, SkippingChangesNoPixelAndEarlyTerminationNoChannelByMoreThan1Of255) {
  // Several balls with empty bricks between them; opaque enough that rays terminate early.
  const Volume volume = test::ballsVolume(
      {64, 64, 64}, {{{16, 16, 20}, 9.0}, {{46, 40, 44}, 12.0}, {{20, 48, 30}, 6.0}}, 4.0);
  for (const std::string effects : {"", "boundary,silhouette,halo,tone,distance"}) {
    RenderSettings settings = illustrateSettings(effects, "k_os=3", {96, 96});
    const RenderResult reference = [&] {
      RenderSettings s = settings;
      s.emptySpaceSkipping = false;
      s.earlyRayTermination = false;
      return test::renderOnce(volume, s);
    }();
    RenderSettings skipping = settings;
    skipping.earlyRayTermination = false;
    const RenderResult skipped = test::renderOnce(volume, skipping);
    EXPECT_GT(test::shownPixels(reference.frame), 1000);
    EXPECT_EQ(test::differingPixels(reference.frame, skipped.frame), 0) << "effects " << effects;
    const RenderResult both = test::renderOnce(volume, settings);
    EXPECT_LE(test::maxChannelDifference(reference.frame.color, both.frame.color), 1.0 / 255.0)
        << "effects " << effects;
  }
}

TEST_F(IllustrateTest, OpacityIsCorrectedForTheSliceDistance) {
  // Twice the slices at the corrected opacity each: the same image to within 2/255.
  const Volume volume = generateVolume("sphere:48");
  RenderSettings settings = illustrateSettings("boundary,tone", "k_os=0.5");
  const RenderResult once = test::renderOnce(volume, settings);
  settings.samplesPerVoxel = 2.0;
  const RenderResult twice = test::renderOnce(volume, settings);
  EXPECT_LE(test::maxChannelDifference(once.frame.color, twice.frame.color), 2.0 / 255.0);
}

}  // namespace
}  // namespace vsil
