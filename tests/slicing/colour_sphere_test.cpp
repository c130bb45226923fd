// demip's colour sphere from an equirectangular PNG (slicing/techniques/mip/colour_sphere.h):
// the convention, GL against the CPU reference, a uniform map, a map drawn from the red-blue
// formula against the built-in red-blue, and the legend. The maps are written here.
#include <cmath>
#include <filesystem>
#include <functional>
#include <numbers>
#include <string>

#include <gtest/gtest.h>

#include "core/image_file.h"
#include "frame_compare.h"
#include "generators/generators.h"
#include "gl_harness.h"
#include "reference_table.h"
#include "slicing/renderer.h"
#include "slicing/technique_table.h"
#include "slicing/techniques/mip/colour_sphere.h"
#include "test_support.h"

namespace vsil {
namespace {

constexpr double kPi = std::numbers::pi;

// A width × height map whose texel (x, y) has the straight RGB colour `colour(λ, φ)` of its
// centre's longitude and latitude (colour_sphere.h), in 8 bits.
std::string writeMap(const std::string& name, int width, int height,
                     const std::function<glm::dvec3(double, double)>& colour) {
  cv::Mat3b bgr(height, width);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const double longitude = ((x + 0.5) / width - 0.5) * 2 * kPi;
      const double latitude = (0.5 - (y + 0.5) / height) * kPi;
      const glm::dvec3 c = glm::clamp(colour(longitude, latitude), 0.0, 1.0);
      bgr(y, x) = cv::Vec3b(cv::saturate_cast<std::uint8_t>(std::lround(c.b * 255)),
                            cv::saturate_cast<std::uint8_t>(std::lround(c.g * 255)),
                            cv::saturate_cast<std::uint8_t>(std::lround(c.r * 255)));
    }
  }
  const auto path = test::scratchDir() / name;
  writePng(path, bgr);
  return path.string();
}

// The red-blue formula: red toward the front, blue at the back, linear in the cosine to the
// front, cos φ·cos λ.
glm::dvec3 redBlue(double longitude, double latitude) {
  const double facing = std::cos(latitude) * std::cos(longitude);
  return glm::mix(glm::dvec3(0, 0, 1), glm::dvec3(1, 0, 0), 0.5 + 0.5 * facing);
}

// A smooth map that differs in every direction: red with longitude (continuous across the
// back), green with latitude, blue with both.
glm::dvec3 smoothMap(double longitude, double latitude) {
  return {0.5 + 0.4 * std::sin(longitude), 0.5 + 0.45 * std::sin(latitude),
          0.5 + 0.3 * std::cos(longitude) * std::cos(latitude)};
}

RenderSettings demipSettings(OptionValues options, double azimuth = 30, double elevation = 20) {
  RenderSettings settings;
  settings.technique = "demip";
  settings.options = std::move(options);
  settings.size = {112, 96};
  settings.camera.azimuthDeg = azimuth;
  settings.camera.elevationDeg = elevation;
  settings.camera.zoom = 1.3;
  return settings;
}

// The largest channel difference over the pixels both frames show, and how many there are.
struct ShownDifference {
  double largest = 0;
  int shown = 0;
};
ShownDifference compareShown(const cv::Mat4f& a, const cv::Mat4f& b) {
  ShownDifference d;
  for (int y = 0; y < a.rows; ++y) {
    for (int x = 0; x < a.cols; ++x) {
      if (!(a(y, x)[3] > 0) || !(b(y, x)[3] > 0)) continue;
      ++d.shown;
      for (int k = 0; k < 4; ++k) {
        d.largest = std::max(d.largest, double(std::abs(a(y, x)[k] - b(y, x)[k])));
      }
    }
  }
  return d;
}

TEST(ColourSphereConvention, TheImageCentreFacesTheViewerAndTheTopRowIsUp) {
  const auto uv = [](glm::vec3 d) { return sphereMapTexCoord(d); };
  EXPECT_EQ(uv({0, 0, 1}), glm::vec2(0.5f, 0.5f)) << "front: the centre";
  EXPECT_NEAR(uv({1, 0, 0}).x, 0.75f, 1e-6) << "the sphere's right: three quarters across";
  EXPECT_NEAR(uv({-1, 0, 0}).x, 0.25f, 1e-6);
  EXPECT_NEAR(uv({0, 0, -1}).x, 1.0f, 1e-6) << "the back: the edge";
  EXPECT_NEAR(uv({0, 1, 0}).y, 0.0f, 1e-6) << "up: the top row";
  EXPECT_NEAR(uv({0, -1, 0}).y, 1.0f, 1e-6);
  EXPECT_NEAR(uv({1, 1, 0}).y, 0.25f, 1e-6) << "45° up";
  EXPECT_TRUE(isSphereMapFile("maps/Earth.PNG"));
  EXPECT_FALSE(isSphereMapFile("red-blue"));
  EXPECT_FALSE(isSphereMapFile("map.jpg"));
}

TEST(ColourSphereConvention, TheFrameTurnsAsTheViewOrbitsAndHoldsItsFront) {
  OptionReader options(findTechnique("demip").options, {{"sphere-rotate", std::string("40,25")}});
  const glm::mat3 frame = sphereFrameEye(options, View{});
  EXPECT_NEAR(glm::length(glm::cross(frame[0], frame[1]) - frame[2]), 0.0f, 1e-6)
      << "right-handed and orthonormal";
  EXPECT_NEAR(glm::dot(frame[0], frame[1]), 0.0f, 1e-6);
  EXPECT_EQ(frame[2], sphereFrontEye(options, View{}));
  EXPECT_NEAR(frame[0].y, 0.0f, 1e-6) << "the azimuth turns about up; right stays level";
}

using ColourSphereGl = test::GlTest;

TEST_F(ColourSphereGl, PngMapMatchesTheCpuReference) {
  const std::string map = writeMap("smooth.png", 96, 48, smoothMap);
  const Volume volume = generateVolume("blobs:48");
  struct Case {
    const char* name;
    OptionValues options;
    double azimuth;
    bool orthographic;
  };
  const Case cases[] = {
      {"view frame", {}, 30, false},
      {"turned, volume frame",
       {{"sphere-rotate", std::string("40,25")}, {"sphere-frame", std::string("volume")}},
       110,
       true},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    OptionValues options = c.options;
    options["sphere-map"] = map;
    options["sphere-weight"] = 0.6;
    RenderSettings settings = demipSettings(options, c.azimuth);
    settings.camera.orthographic = c.orthographic;
    const RenderResult gl = test::renderOnce(volume, settings);
    const reference::ReferenceFrame cpu =
        reference::findReference("demip").render(volume, settings, 1e-4f);
    // Pixels whose first hit may lie on another slice (the reference's ambiguous ones: a value
    // near the threshold, or a position the shader's rounding may tip) are left out; everywhere
    // else the first hit must be the reference's. (With demip's slice passes one pixel of the
    // turned orthographic view disagreed; the march, which a volume in one texture gets, does
    // not.)
    int shown = 0, otherHit = 0;
    double largest = 0;
    for (int y = 0; y < settings.size.y; ++y) {
      for (int x = 0; x < settings.size.x; ++x) {
        shown += cpu.frame.color(y, x)[3] > 0;
        if (cpu.ambiguous(y, x)) continue;
        const float glDepth = gl.frame.depth(y, x), cpuDepth = cpu.frame.depth(y, x);
        if (!std::isnan(cpuDepth) && glDepth != cpuDepth) {
          ++otherHit;
          continue;
        }
        for (int k = 0; k < 4; ++k) {
          largest = std::max(largest,
                             double(std::abs(gl.frame.color(y, x)[k] - cpu.frame.color(y, x)[k])));
        }
      }
    }
    std::cout << "[ info ] " << c.name << ": " << shown << " pixels shown, largest difference "
              << largest << "; " << otherHit << " pixels with another first hit\n";
    EXPECT_EQ(otherHit, 0);
    EXPECT_GT(shown, 1000);
    // As the demip entry of the reference table: float rounding only (here also GLSL's atan
    // against std::atan2 on a map whose colours change by at most 0.4 per radian).
    EXPECT_LT(largest, 1e-4);
  }
}

TEST_F(ColourSphereGl, AUniformPngGivesThatColoursBlend) {
  const glm::dvec3 colour(64 / 255.0, 128 / 255.0, 192 / 255.0);
  const std::string map = writeMap("uniform.png", 8, 4, [&](double, double) { return colour; });
  const Volume volume = generateVolume("blobs:48");
  // With no depth weighting demip's colour is mip's grey·(1 − w) + sphere·w.
  const double w = 0.4;
  const RenderResult demip = test::renderOnce(
      volume, demipSettings({{"sphere-map", map}, {"sphere-weight", w}, {"depth-weight", 0.0}}));
  RenderSettings mipSettings = demipSettings({});
  mipSettings.technique = "mip";
  const RenderResult mip = test::renderOnce(volume, mipSettings);
  cv::Mat4f expected = mip.frame.color.clone();
  for (auto it = expected.begin(); it != expected.end(); ++it) {
    if (!((*it)[3] > 0)) continue;
    for (int k = 0; k < 3; ++k) (*it)[k] = float((*it)[k] * (1 - w) + colour[k] * w);
  }
  const ShownDifference d = compareShown(demip.frame.color, expected);
  EXPECT_GT(d.shown, 1000);
  EXPECT_LT(d.largest, 1e-5) << "bilinear weights of equal texels: float rounding only";
}

TEST_F(ColourSphereGl, APngDrawnFromTheRedBlueFormulaLooksLikeRedBlue) {
  const std::string map = writeMap("red_blue.png", 256, 128, redBlue);
  const Volume volume = generateVolume("blobs:48");
  for (const OptionValues& turn :
       {OptionValues{}, OptionValues{{"sphere-rotate", std::string("60,30")},
                                     {"sphere-frame", std::string("volume")}}}) {
    OptionValues options = turn;
    options["sphere-weight"] = 1.0;  // the sphere's colour alone
    options["sphere-map"] = std::string("red-blue");
    const RenderResult builtin = test::renderOnce(volume, demipSettings(options, 50));
    options["sphere-map"] = map;
    const RenderResult png = test::renderOnce(volume, demipSettings(options, 50));
    const ShownDifference d = compareShown(builtin.frame.color, png.frame.color);
    std::cout << "[ info ] " << d.shown << " pixels, largest difference " << d.largest * 255
              << "/255\n";
    EXPECT_GT(d.shown, 1000);
    // 8-bit texels (0.5/255) and bilinear interpolation of a smooth function between texel
    // centres 1.4° apart (a few 1e-5).
    EXPECT_LT(d.largest, 1.0 / 255);
  }
}

TEST_F(ColourSphereGl, AMapFileIsReadOncePerNameNotPerFrame) {
  const auto uniformMap = [](const std::string& name, glm::dvec3 colour) {
    return writeMap(name, 8, 4, [colour](double, double) { return colour; });
  };
  const std::string first = uniformMap("once_a.png", {1, 0, 0});
  const Volume volume = generateVolume("blobs:48");
  Renderer renderer(test::sharedGlContext());
  renderer.setVolume(volume);
  const RenderSettings settings = demipSettings({{"sphere-map", first}, {"sphere-weight", 1.0}});
  const RenderResult before = renderer.render(settings);
  // A later frame with the same map does not read the file again (nor upload it): blue
  // written over it under the same name does not show.
  uniformMap("once_a.png", {0, 0, 1});
  const RenderResult again = renderer.render(settings);
  EXPECT_EQ(test::differingPixels(before.frame, again.frame), 0);
  // Another name is read.
  const std::string second = uniformMap("once_b.png", {0, 0, 1});
  const RenderResult other =
      renderer.render(demipSettings({{"sphere-map", second}, {"sphere-weight", 1.0}}));
  const ShownDifference d = compareShown(before.frame.color, other.frame.color);
  EXPECT_GT(d.shown, 1000);
  EXPECT_GT(d.largest, 0.99) << "red, then blue";
}

TEST_F(ColourSphereGl, TheLegendDrawsThePngMapAsUsed) {
  // Green in the image's middle half of longitudes (the front), magenta elsewhere.
  const std::string map = writeMap("halves.png", 64, 32, [](double longitude, double) {
    return std::abs(longitude) < kPi / 2 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 1);
  });
  const Volume volume = generateVolume("blobs:48");
  OptionValues options = {{"legend", true}, {"sphere-map", map}};
  const RenderResult plain = test::renderOnce(volume, demipSettings(options));
  options["sphere-rotate"] = std::string("180,0");
  const RenderResult turned = test::renderOnce(volume, demipSettings(options));
  const int radius = 96 / 10, margin = radius / 4;
  const cv::Point centre(112 - margin - radius - 1, 96 - margin - radius - 1);
  EXPECT_EQ(plain.frame.color(centre), cv::Vec4f(1, 1, 1, 1)) << "the cross";
  // Half way to the rim toward the viewer: the front, green; turned, the back, magenta.
  const cv::Point nearCentre = centre + cv::Point(radius / 3, radius / 3);
  EXPECT_EQ(plain.frame.color(nearCentre), cv::Vec4f(0, 1, 0, 1));
  EXPECT_EQ(turned.frame.color(nearCentre), cv::Vec4f(1, 0, 1, 1));
}

}  // namespace
}  // namespace vsil
