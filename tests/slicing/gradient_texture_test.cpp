// The gradient texels (slicing/gradient_texture.h) against a volume whose gradient is known: a
// linear ramp, whose central differences are exact inside and one-sided halves at the border.
#include "slicing/gradient_texture.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "slicing/volume_texture.h"

namespace vsil {
namespace {

// f = 2x + 3y + 4z in voxel indices, spacing (0.5, 1, 2): ∇f = (4, 3, 2) in physical units.
constexpr glm::ivec3 kDims(6, 5, 4);
constexpr glm::dvec3 kSpacing(0.5, 1, 2);
float rampAt(int x, int y, int z) {
  return float(2 * x + 3 * y + 4 * z);
}

std::vector<float> rampSamples() {
  std::vector<float> samples;
  for (int z = 0; z < kDims.z; ++z)
    for (int y = 0; y < kDims.y; ++y)
      for (int x = 0; x < kDims.x; ++x) samples.push_back(rampAt(x, y, z));
  return samples;
}

// Half floats hold g/M to 11 bits.
void expectNear(glm::vec4 actual, glm::vec4 expected, const char* where) {
  for (int c = 0; c < 4; ++c) {
    EXPECT_NEAR(actual[c], expected[c], 1e-3 * std::max(1.0f, std::abs(expected[c])))
        << where << " channel " << c;
  }
}

TEST(GradientTexels, HoldTheGradientOverItsLargestMagnitudeAndTheValueWhenAsked) {
  const std::vector<float> samples = rampSamples();
  const float magnitude = std::sqrt(29.0f);  // |(4, 3, 2)|, the interior's and the largest
  for (bool withValues : {false, true}) {
    const GradientTexels texels =
        computeGradientTexels(samples.data(), kDims, kSpacing, withValues);
    SCOPED_TRACE(withValues ? "with values" : "without values");
    EXPECT_FLOAT_EQ(texels.maxMagnitude, magnitude);
    EXPECT_EQ(texels.holdsValues, withValues);
    const auto value = [&](int x, int y, int z) { return withValues ? rampAt(x, y, z) : 0.0f; };
    expectNear(texels.at(2, 2, 1), glm::vec4(glm::vec3(4, 3, 2) / magnitude, value(2, 2, 1)),
               "interior");
    // At x = 0 and z = 3 the difference spans one voxel instead of two: half the slope.
    expectNear(texels.at(0, 2, 3), glm::vec4(glm::vec3(2, 3, 1) / magnitude, value(0, 2, 3)),
               "border");
  }
}

TEST(GradientTexels, AConstantVolumeHasNoGradient) {
  const std::vector<float> samples(std::size_t(kDims.x) * kDims.y * kDims.z, 7.0f);
  const GradientTexels texels = computeGradientTexels(samples.data(), kDims, kSpacing, true);
  EXPECT_EQ(texels.maxMagnitude, 0.0f);
  expectNear(texels.at(1, 1, 1), glm::vec4(0, 0, 0, 7), "interior");
}

TEST(GradientTexels, HoldValuesOnlyWhereTheVolumeTextureIsExactInHalfFloats) {
  EXPECT_TRUE(gradientsCanHoldValues(GL_R16F));
  EXPECT_FALSE(gradientsCanHoldValues(GL_R32F));
}

}  // namespace
}  // namespace vsil
