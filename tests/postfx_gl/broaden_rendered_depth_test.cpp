// Depth-adaptive widths on a GL render: four spheres at different eye depths in one orthographic
// frame. A sphere's silhouette lies where the view rays graze it, at its centre's depth, so each
// ring must come out with the law's width at the centre's normalized depth (View, not the
// rendered depth image, gives the expected value). A sweep of near/far widths moves them all.
#include <iomanip>
#include <iostream>
#include <sstream>

#include <gtest/gtest.h>

#include "digital_curves.h"
#include "gl_harness.h"
#include "postfx/broaden.h"
#include "rendered_scenes.h"
#include "width_tolerances.h"

namespace vsil {
namespace {

using test::depthTolerance;

struct NearFar {
  double near, far;
};

class RenderedDepthWidths : public test::GlTest {
 protected:
  // Rendered once for the whole sweep.
  static void SetUpTestSuite() {
    test::sharedGlContext().makeCurrent();
    // A 2×2 grid in the image, each ball at its own depth (larger z is nearer at azimuth 0).
    balls_ = {{{32.4, 33.1, 106.2}, 18.0},
              {{95.7, 32.6, 78.9}, 18.0},
              {{31.8, 95.3, 49.3}, 18.0},
              {{96.2, 94.8, 21.7}, 18.0}};
    result_ = new RenderResult(
        test::renderOrthographic(test::ballsVolume({128, 128, 128}, balls_), {400, 400}, 0, 0));
  }
  static void TearDownTestSuite() {
    delete result_;
    result_ = nullptr;
  }
  static inline std::vector<test::Ball> balls_;
  static inline RenderResult* result_ = nullptr;
};

// The band pixels nearest to ball `index`'s projected centre (all balls are the same size, so
// this is also the nearest outline), so that neighbouring rings do not count.
cv::Mat1b bandOfBall(const cv::Mat1b& band, const std::vector<cv::Point2d>& centres,
                     std::size_t index) {
  cv::Mat1b own(band.size(), std::uint8_t(0));
  for (int y = 0; y < band.rows; ++y) {
    for (int x = 0; x < band.cols; ++x) {
      if (!band(y, x)) continue;
      std::size_t nearest = 0;
      for (std::size_t i = 1; i < centres.size(); ++i) {
        if (cv::norm(cv::Point2d(x, y) - centres[i]) <
            cv::norm(cv::Point2d(x, y) - centres[nearest])) {
          nearest = i;
        }
      }
      own(y, x) = nearest == index ? 255 : 0;
    }
  }
  return own;
}

TEST_F(RenderedDepthWidths, SpheresAtDifferentDepthsGetTheLawsWidths) {
  const View& view = result_->view;
  std::vector<cv::Point2d> centres;
  std::vector<double> depths;
  for (const auto& ball : balls_) {
    centres.push_back(test::pixelOfVoxel(view, ball.centreVoxel));
    depths.push_back(
        view.normalizedDepth(-(view.eyeFromVoxel * glm::dvec4(ball.centreVoxel, 1)).z));
  }
  const double radius = balls_[0].radiusVoxels * test::pixelsPerVoxel(view);
  // The rings must be far enough apart for the widest band (W/2 + 1 beyond the circle).
  ASSERT_GT(cv::norm(centres[0] - centres[1]), 2 * (radius + 21 + 2));

  FftGaussianBlur blur;
  for (const NearFar nearFar :
       {NearFar{2, 40}, NearFar{40, 2}, NearFar{3, 13}, NearFar{13, 3}, NearFar{8, 21},
        NearFar{21, 8}, NearFar{5, 40}, NearFar{2, 8}, NearFar{30, 20}}) {
    const WidthLaw law = WidthLaw::depthAdaptive(nearFar.near, nearFar.far);
    const cv::Mat1b band = broadenSilhouettes(result_->frame, law, blur);
    std::ostringstream row;
    row << "near " << std::setw(2) << nearFar.near << " far " << std::setw(2) << nearFar.far << ":";
    for (std::size_t i = 0; i < balls_.size(); ++i) {
      const double expected = law.widthAt(depths[i]);
      const double measured = test::ringBandWidth(bandOfBall(band, centres, i), centres[i], radius,
                                                  radius + law.maxWidth() + 8);
      row << " d=" << std::fixed << std::setprecision(2) << depths[i] << " " << measured << "/"
          << expected;
      EXPECT_NEAR(measured, expected, depthTolerance(expected))
          << "sphere " << i << " at depth " << depths[i] << ", law " << nearFar.near << ".."
          << nearFar.far;
    }
    std::cout << row.str() << "\n";
  }
}

// The rendered silhouette depths are the ones the expectations above assume.
TEST_F(RenderedDepthWidths, SilhouetteDepthsAreTheCentresDepths) {
  const View& view = result_->view;
  for (const auto& ball : balls_) {
    const cv::Point2d centre = test::pixelOfVoxel(view, ball.centreVoxel);
    const double radius = ball.radiusVoxels * test::pixelsPerVoxel(view);
    const double expected =
        view.normalizedDepth(-(view.eyeFromVoxel * glm::dvec4(ball.centreVoxel, 1)).z);
    int count = 0;
    for (int y = 0; y < result_->frame.height(); ++y) {
      for (int x = 0; x < result_->frame.width(); ++x) {
        if (PixelState(result_->frame.state(y, x)) != PixelState::Silhouette) continue;
        if (cv::norm(cv::Point2d(x, y) - centre) > radius + 2) continue;
        ++count;
        // Half a slice of quantization either way (tests/slicing/silhouette_analytic_test).
        EXPECT_NEAR(result_->frame.depth(y, x), expected, 1.0 / result_->sliceCount + 1e-6)
            << "at (" << x << ", " << y << ")";
      }
    }
    EXPECT_GT(count, 100);
  }
}

}  // namespace
}  // namespace vsil
