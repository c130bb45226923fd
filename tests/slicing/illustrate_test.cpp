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
#include "core/illustration.h"
#include "frame_compare.h"
#include "generators/generators.h"
#include "gl_harness.h"
#include "illustrate_reference.h"
#include "slicing/gradient_texture.h"
#include "slicing/renderer.h"
#include "slicing/techniques/illustrate/halo_mask.h"

namespace vsil {
namespace {

struct EffectCase {
  std::string name;
  std::string effects;
  std::string params;  // --param, "" for the defaults
  bool transferFunction = false;
  std::string haloMode = "";  // "" for the default (field)
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

// The power opacity v² in ivory over values 0 .. 1, written as a transfer function: the tests
// of each effect at its defaults classify the analytic balls so, whatever the default
// classification does with their soft fringes (it starts at Otsu's threshold, which leaves the
// fringe a silhouette or halo acts on transparent).
std::string fullRangePowerOpacity() {
  const auto file = std::filesystem::temp_directory_path() /
                    ("vsil_illustrate_power_" + std::to_string(::getpid()) + ".json");
  std::ofstream out(file);
  out << "[";
  for (int i = 0; i <= 16; ++i) {
    const double v = i / 16.0;
    out << (i ? ", " : "") << R"({"color": "#fffff0", "value": )" << v << R"(, "opacity": )"
        << v * v << "}";
  }
  out << "]";
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

// illustrateSettings seen head-on from the front (+z), orthographic, at 96²: a ball is a disc,
// its centre row crossing the rim.
RenderSettings headOn(const std::string& effects, const std::string& params = "") {
  RenderSettings settings = illustrateSettings(effects, params, {96, 96});
  settings.camera.orthographic = true;
  settings.camera.azimuthDeg = 0;
  settings.camera.elevationDeg = 0;
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
    {"halo_exact", "halo", "k_os=0.3", false, "exact"},
    {"all_exact", "boundary,silhouette,fading,sketch,distance,halo,tone", "k_os=0.3", false,
     "exact"},
    {"transfer_function_all_exact", "boundary,silhouette,fading,distance,halo,tone", "", true,
     "exact"},
};

class IllustrateMatchesReference
    : public test::GlTest,
      public ::testing::WithParamInterface<std::tuple<EffectCase, bool>> {};

TEST_P(IllustrateMatchesReference, EveryChannelWithin2Of255) {
  const auto& [c, eightBit] = GetParam();
  const Volume volume = eightBit ? eightBitSphere() : generateVolume("sphere:48");
  RenderSettings settings = illustrateSettings(c.effects, c.params);
  if (c.transferFunction) settings.options["tf"] = sphereTransferFunction(eightBit ? 255 : 1);
  if (!c.haloMode.empty()) settings.options["halo-mode"] = c.haloMode;
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
  RenderSettings settings = illustrateSettings("tone", "k_os=2", {80, 80});  // ivory
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

// Lit side warm, far side cool, the highlight not clipped (frame_compare.h); k_os = 2 keeps
// the ball opaque, in illustrate's default ivory.
TEST_F(IllustrateTest, ToneShadedIvoryIsWarmWhereLitCoolWhereNotAndNotClipped) {
  test::expectIvoryToneWarmWhereLitCoolWhereNotAndNotClipped(generateVolume("sphere:48"),
                                                             headOn("tone", "k_os=2"));
}

TEST_F(IllustrateTest, SilhouetteEnhancementRaisesOpacityAtTheRimNotWhereTheSphereFacesTheViewer) {
  // A ball whose inside is flat (no gradient: counts as facing the viewer); gen:sphere's cone
  // has an apex whose interpolated normals point anywhere.
  const Volume volume = test::ballsVolume({64, 64, 64}, {{{31.5, 31.5, 31.5}, 20.0}}, 8.0);
  // k_se = 1: with the paper's 0.25, (1 − |n·v|)^k_se reaches 0.1 already at |n·v| = 0.9999,
  // so the trilinear normals' rounding along the centre ray would enhance it too.
  RenderSettings settings = headOn("silhouette", "k_os=0.05,k_se=1");
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
  for (const std::string mode : {"field", "exact"}) {
    SCOPED_TRACE("halo mode " + mode);
    RenderSettings settings = headOn("halo", "k_os=1,k_hr=4");
    settings.options["halo-mode"] = mode;
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
    std::cout << "[ info ] " << mode << ": edge x " << edge << ": alpha outside " << outsideAlpha
              << " (plain " << plain.frame.color(y, edge + 2)[3] << ")\n";
    EXPECT_GT(outsideAlpha, plain.frame.color(y, edge + 2)[3] + 0.05f);
    // Composed over white, darker there.
    const cv::Vec4f h = halo.frame.color(y, edge + 2);
    EXPECT_LT(h[0] + (1 - h[3]), 1.0f - 0.05f) << "the halo should darken the background";
    // Inside, around the centre: nothing changes (the neighbours' normals point away from it);
    // 1e-4 (0.03/255) allows float rounding in the halo program's different instruction order
    // and the black of halos of about 1e-4 in the ball's fringe in front. The field's 3D
    // neighbourhood also pushes the fringe in front from the surface behind it (the slice
    // plane's taps never look there); its mean normal faces the viewer up to the ball's
    // curvature, so (1 − |N·V|)^k_hse lets a trace through: 1.5e-3 (0.4/255; measured 1.1e-3).
    const float tolerance = mode == "field" ? 1.5e-3f : 1e-4f;
    for (int x = 40; x <= 56; ++x) {
      for (int k = 0; k < 4; ++k) {
        EXPECT_NEAR(halo.frame.color(y, x)[k], plain.frame.color(y, x)[k], tolerance) << "x " << x;
      }
    }
  }
}

TEST(HaloField, PushesOutwardJustOutsideABallAndNothingInsideOrFarAway) {
  // A ball of radius 10 with a flat inside and a 2-voxel ramp, visible above 0.5, k_hr 4 (the
  // field's neighbours at 3 voxels): just outside its surface, F > 0 and N points outward
  // (radially); at its centre (no gradient within reach) F = 0; far outside, nothing at all
  // (alpha 0: no halo and transparent, so samples there leave before the volume fetch).
  const glm::ivec3 dims(40, 40, 40);
  const glm::dvec3 centre(19.5, 19.5, 19.5);
  const Volume volume = test::ballsVolume(dims, {{centre, 10.0}}, 2.0);
  std::vector<float> samples(std::size_t(dims.x) * dims.y * dims.z);
  for (std::size_t i = 0; i < samples.size(); ++i) samples[i] = float(volume.value(i));
  const auto visible = [](float value) { return value > 0.5f; };
  const std::vector<std::uint8_t> mask = haloMaskVoxels(samples.data(), dims, visible, 4.0);
  const GradientTexels gradients =
      computeGradientTexels(samples.data(), dims, glm::dvec3(1.0), /*withValues=*/false);
  const std::vector<std::uint8_t> field = haloFieldVoxels(
      gradients, mask, samples.data(), [](float, float hi) { return !(hi > 0.5f); },
      glm::dvec3(1.0), 4.0, 1.0);
  const auto at = [&](glm::ivec3 p) {
    return &field[4 * ((std::size_t(p.z) * dims.y + p.y) * dims.x + p.x)];
  };
  // Just outside, along each axis and a diagonal: about 2 voxels beyond radius 10.
  for (const glm::dvec3 direction : {glm::dvec3(1, 0, 0), glm::dvec3(0, -1, 0), glm::dvec3(0, 0, 1),
                                     glm::normalize(glm::dvec3(1, 1, 0))}) {
    const glm::ivec3 p(glm::floor(centre + direction * 12.0 + 0.5));
    SCOPED_TRACE(testing::Message() << "voxel " << p.x << "," << p.y << "," << p.z);
    const std::uint8_t* bytes = at(p);
    EXPECT_GT(haloFieldStrength(bytes[3]), 0.01f);
    EXPECT_GT(glm::dot(haloFieldNormal(bytes), glm::vec3(direction)), 0.9f);
  }
  EXPECT_EQ(haloFieldStrength(at({19, 19, 19})[3]), 0.0f);  // the centre
  EXPECT_EQ(at({19, 19, 19})[3], 1);                        // no halo, but visible
  EXPECT_EQ(at({0, 0, 0})[3], 0);                           // a corner: nothing
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
  RenderSettings settings = headOn("distance", "k_os=4,k_de=1");
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

// Each effect alone at its default parameters (and the default classification, k_os = 1) must
// show, where the paper says it acts, and change nothing elsewhere (issue 32: boundary changed
// 2/255, halos glowed pale, sketch alone drew a black blob). Seen head-on, orthographic.

// A premultiplied pixel over `background` (grey level in [0, 1]), the mean of its channels.
float over(const cv::Vec4f& c, float background = 1.0f) {
  return (c[0] + c[1] + c[2]) / 3.0f + (1.0f - c[3]) * background;
}

// The outermost pixel of row y, right of x0, where the frame shows anything.
int rimOf(const cv::Mat4f& color, int y, int x0) {
  int rim = x0;
  while (rim + 1 < color.cols && color(y, rim + 1)[3] > 1e-3f) ++rim;
  return rim;
}

TEST_F(IllustrateTest, BoundaryAtItsDefaultsFadesAFlatInsideAndLeavesTheBackground) {
  // A ball with a sharp boundary (ramp 2 voxels) and a flat inside (no gradient).
  const Volume volume = test::ballsVolume({64, 64, 64}, {{{31.5, 31.5, 31.5}, 20.0}}, 2.0);
  RenderSettings settings = headOn("boundary");
  const RenderResult boundary = test::renderOnce(volume, settings);
  settings.options.erase("effects");
  const RenderResult plain = test::renderOnce(volume, settings);
  double change = 0;
  int object = 0, background = 0;
  for (int y = 0; y < 96; ++y) {
    for (int x = 0; x < 96; ++x) {
      const cv::Vec4f p = plain.frame.color(y, x), b = boundary.frame.color(y, x);
      if (p[3] > 0.5f) {
        change += std::abs(over(b) - over(p));
        ++object;
      } else if (p[3] == 0.0f) {
        EXPECT_EQ(b, p) << "background changed at " << x << "," << y;
        ++background;
      }
    }
  }
  ASSERT_GT(object, 1000);
  ASSERT_GT(background, 1000);
  // The opaque inside fades to the two boundary shells: the ball turns translucent.
  const double meanLevels = 255.0 * change / object;
  std::cout << "[ info ] boundary: mean |change| over the ball " << meanLevels << "/255\n";
  EXPECT_GT(meanLevels, 5.0);
  EXPECT_LT(boundary.frame.color(48, 48)[3], plain.frame.color(48, 48)[3] - 0.1f);
}

TEST_F(IllustrateTest, SilhouetteAtItsDefaultsMakesTheOutlineMoreOpaque) {
  const Volume volume = test::ballsVolume({64, 64, 64}, {{{31.5, 31.5, 31.5}, 20.0}}, 8.0);
  RenderSettings settings = headOn("silhouette");
  settings.options["tf"] = fullRangePowerOpacity();
  const RenderResult enhanced = test::renderOnce(volume, settings);
  settings.options.erase("effects");
  const RenderResult plain = test::renderOnce(volume, settings);
  const int y = 48, rim = rimOf(plain.frame.color, y, 48);
  ASSERT_GT(rim, 60);
  // Two pixels inside the plain composite's outline: its soft edge, seen edge-on.
  const float before = plain.frame.color(y, rim - 2)[3],
              after = enhanced.frame.color(y, rim - 2)[3];
  std::cout << "[ info ] silhouette: alpha at the rim " << before << " -> " << after << "\n";
  EXPECT_GT(after - before, 0.2f);
  // The centre (opaque either way) keeps its colour.
  EXPECT_NEAR(over(enhanced.frame.color(y, 48)), over(plain.frame.color(y, 48)), 2.0 / 255.0);
}

TEST_F(IllustrateTest, HalosAtTheirDefaultsDarkenJustOutsideTheOutlineAndNeverBrighten) {
  // gen:sphere's cone, lit: halo samples lie in its soft fringe, whose own lit colour is light.
  const Volume volume = generateVolume("sphere:48");
  for (const Rgba background : {Rgba{255, 255, 255, 255}, Rgba{0, 0, 0, 255}}) {
    RenderSettings settings = headOn("halo");
    settings.options["tf"] = fullRangePowerOpacity();
    settings.background = background;
    const float b = background.r / 255.0f;
    const RenderResult halo = test::renderOnce(volume, settings);
    settings.options.erase("effects");
    const RenderResult plain = test::renderOnce(volume, settings);
    const int y = 48, rim = rimOf(plain.frame.color, y, 48);
    ASSERT_GT(rim, 60);
    ASSERT_LT(rim, 90);
    float darkest = 1.0f;
    for (int x = 40; x < 96; ++x) {
      const float withHalo = over(halo.frame.color(y, x), b),
                  without = over(plain.frame.color(y, x), b);
      // The halo's added opacity is dark: it never brightens a pixel, over any background.
      EXPECT_LE(withHalo, without + 1.0f / 255.0f) << "x " << x << " background " << b;
      if (x > rim - 6) darkest = std::min(darkest, withHalo - without);
    }
    // Inside, around the centre, nothing changes (the neighbours' normals face the viewer);
    // far outside (beyond k_hr = 4 voxels, 2.8 pixels each here) neither.
    for (int x = 44; x <= 52; ++x) {
      EXPECT_NEAR(over(halo.frame.color(y, x), b), over(plain.frame.color(y, x), b), 1.0 / 255.0)
          << "x " << x;
    }
    EXPECT_EQ(halo.frame.color(y, 95), plain.frame.color(y, 95));
    std::cout << "[ info ] halo over " << b << ": darkest change at the outline " << darkest
              << "\n";
    if (b > 0.5f) {
      EXPECT_LT(darkest, -0.3f) << "a dark rim just outside the outline";
    }
  }
}

TEST_F(IllustrateTest, SketchAloneAtItsDefaultsLeavesTheFacingBallClearAndItsOutlineDark) {
  // A ball with a flat inside carrying a little noise (its gradient 1.4 % of the boundary's), as
  // a CT's homogeneous material: the noise's normals point anywhere.
  Volume volume = test::ballsVolume({64, 64, 64}, {{{31.5, 31.5, 31.5}, 20.0}}, 4.0);
  std::mt19937 random(32);
  std::uniform_real_distribution<float> noise(-0.005f, 0.005f);
  for (float& v : volume.samples<float>()) {
    if (v >= 1.0f) v += noise(random);
  }
  const RenderResult sketch = test::renderOnce(volume, headOn("sketch"));
  const cv::Mat4f& c = sketch.frame.color;
  const int y = 48;
  // Facing the viewer (front shell, flat noisy inside): the white background shows through.
  float centre = 1.0f;
  for (int x = 40; x <= 56; ++x) centre = std::min(centre, over(c(y, x)));
  // The outline, right of the centre: its darkest pixel.
  float rim = 1.0f;
  for (int x = 60; x < 96; ++x) rim = std::min(rim, over(c(y, x)));
  std::cout << "[ info ] sketch: darkest pixel of the centre " << centre << ", darkest outline "
            << rim << "\n";
  EXPECT_GT(centre, 0.85f);
  EXPECT_LT(rim, 0.3f);
  EXPECT_EQ(c(y, 95), cv::Vec4f(0, 0, 0, 0));
}

// HSV saturation and value of a premultiplied pixel's straight colour.
std::pair<float, float> saturationAndValue(const cv::Vec4f& c) {
  const float a = std::max(c[3], 1e-6f);
  const float hi = std::max({c[0], c[1], c[2]}) / a, lo = std::min({c[0], c[1], c[2]}) / a;
  return {hi > 0 ? (hi - lo) / hi : 0.0f, hi};
}

TEST_F(IllustrateTest, FadingAtItsDefaultsDesaturatesWhatFacesTheViewerAndDarkensWhatTurnsAway) {
  const Volume volume = test::ballsVolume({64, 64, 64}, {{{31.5, 31.5, 31.5}, 20.0}}, 8.0);
  RenderSettings settings = headOn("fading");
  settings.options["color"] = std::string("#c06040");  // saturated, so desaturation shows
  const RenderResult faded = test::renderOnce(volume, settings);
  settings.options.erase("effects");
  const RenderResult plain = test::renderOnce(volume, settings);
  const int y = 48, rim = rimOf(plain.frame.color, y, 48);
  ASSERT_GT(rim, 60);
  const auto [plainSat, plainValue] = saturationAndValue(plain.frame.color(y, 48));
  const auto [fadedSat, fadedValue] = saturationAndValue(faded.frame.color(y, 48));
  const float plainRim = saturationAndValue(plain.frame.color(y, rim - 3)).second;
  const float fadedRim = saturationAndValue(faded.frame.color(y, rim - 3)).second;
  std::cout << "[ info ] fading: centre saturation " << plainSat << " -> " << fadedSat
            << ", rim value " << plainRim << " -> " << fadedRim << "\n";
  EXPECT_LT(fadedSat, 0.5f * plainSat);        // facing: k_fs = 0.8 takes most of it
  EXPECT_NEAR(fadedValue, plainValue, 0.02f);  // and keeps its value
  EXPECT_LT(fadedRim, 0.75f * plainRim);       // turned away: darker
  EXPECT_EQ(faded.frame.color(y, 95), plain.frame.color(y, 95));
}

TEST_F(IllustrateTest, DistanceAtItsDefaultsBlendsTheFartherPartsMoreTowardTheBackground) {
  const Volume volume = test::ballsVolume({64, 64, 64}, {{{31.5, 31.5, 31.5}, 20.0}}, 8.0);
  RenderSettings settings = headOn("distance");  // c_b: the white background
  const RenderResult blended = test::renderOnce(volume, settings);
  settings.options.erase("effects");
  const RenderResult plain = test::renderOnce(volume, settings);
  const int y = 48, rim = rimOf(plain.frame.color, y, 48);
  ASSERT_GT(rim, 60);
  // The share of the way to white: over white, (blended − plain) / (1 − plain).
  const auto share = [&](int x) {
    const float p = over(plain.frame.color(y, x)), b = over(blended.frame.color(y, x));
    return (b - p) / std::max(1.0f - p, 1e-3f);
  };
  std::cout << "[ info ] distance: share toward the background at the centre " << share(48)
            << ", near the rim " << share(rim - 6) << "\n";
  EXPECT_GT(share(48), 0.2f);                    // the front is a fifth of the way in, d^0.5 > 0.4
  EXPECT_GT(share(rim - 6), share(48) + 0.05f);  // the surface near the rim lies deeper
  EXPECT_EQ(blended.frame.color(y, 95), plain.frame.color(y, 95));
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
