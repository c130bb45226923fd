// The procedural volumes against their formulas in generators/generators.h.
#include "generators/generators.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "core/error.h"
#include "io/volume_loader.h"
#include "io_test_files.h"

namespace vsil {
namespace {

// Samples are stored as float: 1e-6 covers float rounding of values in [0, 1] (ulp 6e-8) and
// the last-bit differences of the separable Gaussian products.
constexpr float kTolerance = 1e-6f;

TEST(Generators, EveryNameMakesAnNCubeOfFloatsInUnitRange) {
  for (const auto& name : generatorNames()) {
    const Volume volume = generateVolume(name + ":33");
    EXPECT_EQ(volume.dims, glm::ivec3(33)) << name;
    EXPECT_EQ(volume.type(), SampleType::Float32) << name;
    EXPECT_EQ(volume.spacing, glm::dvec3(1.0)) << name;
    EXPECT_EQ(volume.name, name);
    EXPECT_EQ(volume.source, "gen:" + name + ":33");
    ASSERT_EQ(volume.sampleCount(), 33u * 33u * 33u) << name;
    const auto range = valueRange(volume);
    EXPECT_GE(range.min, 0.0f) << name;
    EXPECT_LE(range.max, 1.0f) << name;
    EXPECT_GT(range.max, range.min) << name << " is constant";
  }
}

TEST(Generators, DefaultEdgeIs64AndLoadVolumeDispatchesGenPrefix) {
  const Volume volume = loadVolume("gen:sphere");
  EXPECT_EQ(volume.dims, glm::ivec3(64));
  EXPECT_EQ(volume.source, "gen:sphere:64");
}

TEST(Generators, SphereIsOneAtCentreAndHalfAtQuarterEdge) {
  // N odd puts a sample exactly on the centre c = 32; N/2 = 32.5.
  const Volume v = generateVolume("sphere:65");
  EXPECT_NEAR(v.at(32, 32, 32), 1.0f, kTolerance);
  // r = 16 along one axis: f = 1 - 16/32.5.
  EXPECT_NEAR(v.at(48, 32, 32), 1.0 - 16.0 / 32.5, kTolerance);
  EXPECT_NEAR(v.at(32, 32, 16), 1.0 - 16.0 / 32.5, kTolerance);
  EXPECT_EQ(v.at(0, 0, 0), 0.0f);  // r = 55 > N/2: clamped to 0
}

TEST(Generators, SpheresHaveASaddleWaistAboveHalf) {
  // N = 49: c = 24, centres at 24 ∓ 49/6 (not on the grid); midway on the axis the value is
  // 2e^(-8/9) / (1 + e^(-32/9)) independently of N.
  const Volume v = generateVolume("spheres:49");
  const double waist = 2.0 * std::exp(-8.0 / 9.0) / (1.0 + std::exp(-32.0 / 9.0));
  EXPECT_NEAR(v.at(24, 24, 24), waist, kTolerance);
  EXPECT_GT(waist, 0.5);
  // Near each blob centre the value is higher than at the waist (a saddle, not a ridge).
  EXPECT_GT(v.at(16, 24, 24), v.at(24, 24, 24));
  EXPECT_GT(v.at(32, 24, 24), v.at(24, 24, 24));
  // The two blobs are mirror images.
  EXPECT_NEAR(v.at(16, 24, 24), v.at(32, 24, 24), kTolerance);
}

TEST(Generators, TorusIsOneOnItsCoreCircle) {
  // N = 65: c = 32, R = 16.25, falloff N/8 = 8.125. On the x axis at x = c + 16: d = 0.25.
  const Volume v = generateVolume("torus:65");
  EXPECT_NEAR(v.at(48, 32, 32), 1.0 - 0.25 / 8.125, kTolerance);
  EXPECT_NEAR(v.at(32, 16, 32), 1.0 - 0.25 / 8.125, kTolerance);
  EXPECT_EQ(v.at(32, 32, 32), 0.0f);  // the hole: d = R > N/8
  // Above the core circle by 4: d = sqrt(0.25² + 4²).
  EXPECT_NEAR(v.at(48, 32, 36), 1.0 - std::hypot(0.25, 4.0) / 8.125, kTolerance);
}

TEST(Generators, MarschnerLobbMatchesTheFormulaAtCorners) {
  const Volume v = generateVolume("marschner-lobb:41");
  // u = (-1, -1, -1): r = sqrt 2, ρ = cos(12π cos(π√2/2)); f = (1 + 1 + 0.25(1 + ρ)) / 2.5.
  const double pi = std::numbers::pi;
  const double rho = std::cos(12.0 * pi * std::cos(pi * std::sqrt(2.0) / 2.0));
  EXPECT_NEAR(v.at(0, 0, 0), (2.0 + 0.25 * (1.0 + rho)) / 2.5, kTolerance);
  // u = (0, 0, 0): r = 0, ρ = cos(12π) = 1; f = (1 + 0.5) / 2.5 = 0.6.
  EXPECT_NEAR(v.at(20, 20, 20), 0.6, kTolerance);
}

TEST(Generators, HydrogenLobesPeakAtOneAndRingAtHalf) {
  // N = 97: c = 48, a = 97/48, peaks at r = 6a = 12.125 (not on the grid): use the formula.
  const Volume v = generateVolume("hydrogen:97");
  const double a = 97.0 / 48.0;
  auto expected = [&](double qx, double qz) {
    const double r2 = qx * qx + qz * qz;
    return std::abs(3 * qz * qz - r2) * std::exp(-std::sqrt(r2) / (3 * a)) /
           (72 * a * a * std::exp(-2.0));
  };
  EXPECT_NEAR(v.at(48, 48, 60), expected(0, 12), kTolerance);
  EXPECT_GT(v.at(48, 48, 60), 0.99f);  // next to the lobe peak
  EXPECT_NEAR(v.at(60, 48, 48), expected(12, 0), kTolerance);
  EXPECT_NEAR(v.at(60, 48, 48), 0.5, 0.01);  // the ring, half the lobe peak
  EXPECT_EQ(v.at(48, 48, 48), 0.0f);
}

TEST(Generators, AreDeterministic) {
  for (const auto& name : generatorNames()) {
    const Volume a = generateVolume(name + ":24");
    const Volume b = generateVolume(name + ":24");
    EXPECT_TRUE(test::floatsOf(a) == test::floatsOf(b)) << name;
  }
}

TEST(Generators, BadNamesAndEdgesListTheValidNames) {
  for (const char* spec : {"box", "sphere:abc", "sphere:", "sphere:1", "sphere:-4", "sphere:12x",
                           "sphere:99999999999"}) {
    try {
      generateVolume(spec);
      ADD_FAILURE() << spec << " was accepted";
    } catch (const InputError& e) {
      const std::string message = e.what();
      EXPECT_EQ(message.rfind(std::string("gen:") + spec + ": ", 0), 0u) << message;
      EXPECT_NE(message.find("sphere, spheres, torus, marschner-lobb, hydrogen, blobs, cube"),
                std::string::npos)
          << message;
      EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
  }
}

TEST(Generators, EdgeIsCheckedAgainstTheLimits) {
  VolumeLimits limits;
  limits.maxDimension = 100;
  EXPECT_THROW(generateVolume("sphere:101", limits), InputError);
  limits = {};
  limits.maxBytes = 1 << 20;  // 64³ floats = 1 MiB fits, 65³ does not
  EXPECT_NO_THROW(generateVolume("sphere:64", limits));
  EXPECT_THROW(generateVolume("sphere:65", limits), InputError);
}

}  // namespace
}  // namespace vsil
