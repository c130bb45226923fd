// The depth image codec: what render --depth-out writes, measure-width --depth reads back.
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "core/depth_image.h"
#include "core/error.h"

namespace vsil {
namespace {

TEST(DepthImage, RoundTripKeepsDepthToHalfAStepAndNothingStaysNothing) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  cv::Mat1f depth(1, 6);
  depth << nan, 0.0f, 1.0f, 0.25f, 0.999999f, nan;
  const cv::Mat1w encoded = encodeDepthImage(depth);
  EXPECT_EQ(encoded(0, 0), 0) << "no depth is 0";
  EXPECT_EQ(encoded(0, 1), 1) << "depth 0 is 1, never 0";
  EXPECT_EQ(encoded(0, 2), 65535);
  const cv::Mat1f decoded = decodeDepthImage(encoded, "d.png");
  EXPECT_TRUE(std::isnan(decoded(0, 0)));
  EXPECT_TRUE(std::isnan(decoded(0, 5)));
  for (int x = 1; x <= 4; ++x) {
    EXPECT_NEAR(decoded(0, x), depth(0, x), 0.5 / 65534.0) << "at " << x;
  }
}

TEST(DepthImage, OutOfRangeDepthsClampAndOtherImagesAreRefused) {
  cv::Mat1f depth(1, 2);
  depth << -0.5f, 2.0f;
  const cv::Mat1w encoded = encodeDepthImage(depth);
  EXPECT_EQ(encoded(0, 0), 1);
  EXPECT_EQ(encoded(0, 1), 65535);
  EXPECT_THROW(decodeDepthImage(cv::Mat1b(2, 2, std::uint8_t(3)), "grey.png"), InputError);
  EXPECT_THROW(decodeDepthImage(cv::Mat3w(2, 2), "colour.png"), InputError);
}

}  // namespace
}  // namespace vsil
