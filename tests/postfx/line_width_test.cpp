// measure-width's estimator against bands of known width (area / centre length).
#include "postfx/line_width.h"

#include <iostream>

#include <gtest/gtest.h>

#include "digital_curves.h"
#include "postfx/broaden.h"

namespace vsil {
namespace {

TEST(LineWidth, MedianOnBroadenedCirclesMatchesTheAreaWidth) {
  FftGaussianBlur blur;
  for (int width : {2, 3, 5, 8, 13, 21}) {
    const cv::Point2d centre(100.4, 99.7);
    const double radius = 60;
    const cv::Mat1b lines = test::silhouettePixels({200, 200}, test::discShape(centre, radius));
    const cv::Mat1b band = broadenMask(lines, width, blur);
    const double areaWidth = test::ringBandWidth(band, centre, radius, radius + width + 8);
    std::vector<double> widths;
    for (const auto& s : measureLineWidths(band)) widths.push_back(s.width);
    const WidthStatistics stats = summarizeWidths(widths);
    std::cout << "W=" << width << " area " << areaWidth << " mean " << stats.mean << " median "
              << stats.median << " p05 " << stats.p05 << " p95 " << stats.p95 << "\n";
    // A pixel-grid estimate: ±0.5 px or ±5 % of the area-based width.
    EXPECT_NEAR(stats.mean, areaWidth, std::max(0.5, 0.05 * areaWidth)) << "W " << width;
  }
}

TEST(LineWidth, AxisBandsOfEveryIntegerWidth) {
  for (int width = 1; width <= 12; ++width) {
    cv::Mat1b band(60, 80, std::uint8_t(0));
    band.rowRange(20, 20 + width).setTo(255);
    std::vector<double> widths;
    for (const auto& s : measureLineWidths(band)) {
      if (s.pixel.x > 10 && s.pixel.x < 70) widths.push_back(s.width);
    }
    ASSERT_FALSE(widths.empty());
    const WidthStatistics stats = summarizeWidths(widths);
    EXPECT_NEAR(stats.median, width, 0.01) << "band of " << width << " rows";
  }
}

TEST(LineWidth, StatisticsAndHistogram) {
  const WidthStatistics stats = summarizeWidths({1, 2, 2, 3, 10}, 1.0);
  EXPECT_EQ(stats.count, 5);
  EXPECT_DOUBLE_EQ(stats.median, 2);
  EXPECT_DOUBLE_EQ(stats.mean, 3.6);
  ASSERT_EQ(stats.histogram.size(), 11u);
  EXPECT_EQ(stats.histogram[2], 2);
}

}  // namespace
}  // namespace vsil
