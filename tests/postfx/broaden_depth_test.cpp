// Depth-adaptive widths: discs (sphere silhouettes) at different depths in one frame come out
// with the width the law gives at their depth; sweeping the near/far widths moves them as
// predicted.
#include <iomanip>
#include <iostream>
#include <sstream>

#include <gtest/gtest.h>

#include "digital_curves.h"
#include "postfx/broaden.h"
#include "width_tolerances.h"

namespace vsil {
namespace {

using test::depthTolerance;

struct NearFar {
  double near, far;
};

class DepthAdaptive : public ::testing::TestWithParam<NearFar> {};

TEST_P(DepthAdaptive, DiscsAtDifferentDepthsGetTheLawsWidths) {
  const auto [near, far] = GetParam();
  const WidthLaw law = WidthLaw::depthAdaptive(near, far);
  const double radius = 41.3;
  const std::vector<test::DepthDisc> discs = {{{120.4, 119.8}, radius, 0.0},
                                              {{360.7, 120.2}, radius, 0.3},
                                              {{119.6, 360.3}, radius, 0.65},
                                              {{360.2, 359.5}, radius, 1.0}};
  const FrameBuffers frame = test::discsFrame({480, 480}, discs);
  FftGaussianBlur blur;
  const cv::Mat1b band = broadenSilhouettes(frame, law, blur);
  std::ostringstream row;
  row << "near " << near << " far " << far << ":";
  for (const auto& disc : discs) {
    const double expected = law.widthAt(disc.depth);
    const double measured =
        test::ringBandWidth(band, disc.centre, disc.radius, disc.radius + law.maxWidth() + 8);
    row << " d=" << disc.depth << " " << std::fixed << std::setprecision(2) << measured << "/"
        << expected;
    EXPECT_NEAR(measured, expected, depthTolerance(expected))
        << "disc at (" << disc.centre.x << ", " << disc.centre.y << "), depth " << disc.depth;
  }
  std::cout << row.str() << "\n";
}

// The sweep: the same four depths under near/far widths over the whole 2..40 range.
INSTANTIATE_TEST_SUITE_P(NearFarSweep, DepthAdaptive,
                         ::testing::Values(NearFar{2, 40}, NearFar{40, 2}, NearFar{3, 13},
                                           NearFar{13, 3}, NearFar{8, 21}, NearFar{21, 8},
                                           NearFar{5, 40}, NearFar{2, 8}, NearFar{1, 5},
                                           NearFar{30, 20}),
                         [](const auto& info) {
                           return "near" + std::to_string(int(info.param.near)) + "_far" +
                                  std::to_string(int(info.param.far));
                         });

// A fixed law through broadenSilhouettes equals broadenMask of the silhouettes.
TEST(DepthAdaptive, FixedLawIgnoresDepth) {
  const FrameBuffers frame = test::discsFrame({200, 200}, {{{100.3, 99.6}, 50, 0.4}});
  FftGaussianBlur blur;
  const cv::Mat1b viaFrame = broadenSilhouettes(frame, WidthLaw::fixed(9), blur);
  const cv::Mat1b viaMask =
      broadenMask(frame.state == std::uint8_t(PixelState::Silhouette), 9, blur);
  EXPECT_EQ(cv::countNonZero(viaFrame != viaMask), 0);
}

}  // namespace
}  // namespace vsil
