// toneShadingPeak (core/illustration.h): the largest channel of Ebert–Rheingans' tone shading
// sum for a white object, against the sum itself written out here and evaluated over a dense
// set of normals, for one light (where it is the paper's Figure 7 value by hand) and several.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "core/illustration.h"

namespace vsil {
namespace {

// I = k_ta·I_G + Σ_lights (t·(k_ty, k_ty, 0) + (1 − t)·(0, 0, k_tb) + k_td·max(n·L, 0)) for a
// white object, I_G = k_a + k_d·Σ max(n·L, 0), t = (1 + n·L)/2: its largest channel at `n`.
double largestChannel(const Illustration& ill, glm::dvec3 n) {
  double diffuse = 0, warm = 0, cool = 0, directed = 0;
  for (const Light& light : ill.lights) {
    const double nl = glm::dot(n, light.directionEye());
    const double t = (1 + nl) / 2;
    diffuse += std::max(nl, 0.0);
    warm += ill["k_ty"] * t;
    cool += ill["k_tb"] * (1 - t);
    directed += ill["k_td"] * std::max(nl, 0.0);
  }
  const double lit = ill["k_ta"] * (ill["k_a"] + ill["k_d"] * diffuse);
  return lit + directed + std::max(warm, cool);
}

// The largest over 200 000 normals spread evenly over the sphere (a Fibonacci lattice, points
// about 0.008 rad apart): at most 0.004 rad from the maximum, where the sum falls as
// |w|·θ²/2 (|w| < 15 here), so within 1e-3 of it.
double sampledPeak(const Illustration& ill) {
  constexpr int kCount = 200000;
  const double golden = std::numbers::pi * (3 - std::sqrt(5.0));
  double peak = 0;
  for (int i = 0; i < kCount; ++i) {
    const double z = 1 - 2 * (i + 0.5) / kCount, r = std::sqrt(1 - z * z);
    const glm::dvec3 n(r * std::cos(golden * i), r * std::sin(golden * i), z);
    peak = std::max(peak, largestChannel(ill, n));
  }
  return peak;
}

Illustration defaults() {
  return resolveIllustration({}, {}, "");
}

TEST(ToneShadingPeak, OneLightAtTheFigure7ValuesIsTheSumFacingTheLight) {
  const Illustration ill = defaults();  // k_ta 1, k_a 0.3, k_d 0.7, k_ty 0.3, k_tb 0.3, k_td 0.6
  // Facing the light: 1·(0.3 + 0.7) + 0.3 of warm + 0.6 directed, in red and green.
  EXPECT_NEAR(toneShadingPeak(ill), 1.9, 1e-12);
  EXPECT_NEAR(sampledPeak(ill), 1.9, 1e-4);
}

TEST(ToneShadingPeak, MatchesTheSumOverEveryNormalForSeveralLightsAndParameters) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int trial = 0; trial < 12; ++trial) {
    Illustration ill = defaults();
    ill.lights.clear();
    const int lights = 1 + trial % 4;
    for (int i = 0; i < lights; ++i) {
      ill.lights.push_back(Light{360 * unit(random) - 180, 180 * unit(random) - 90});
    }
    for (const char* name : {"k_ta", "k_td", "k_ty", "k_tb", "k_a", "k_d"}) {
      ill.parameters[name] = 1.5 * unit(random);
    }
    if (trial == 11) ill.parameters["k_tb"] = 5;  // the cool side the brighter: peaks away
    SCOPED_TRACE(trial);
    const double peak = toneShadingPeak(ill), sampled = sampledPeak(ill);
    EXPECT_GE(peak, sampled - 1e-9) << "never below the sum somewhere";
    EXPECT_LT(peak, sampled + 2e-3) << "reached, up to the sampling";
  }
}

}  // namespace
}  // namespace vsil
