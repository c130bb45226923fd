// measure-width's estimator against bands of known width (area / centre length).
#include "postfx/line_width.h"

#include <cmath>
#include <iostream>
#include <numbers>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "core/error.h"

#include "digital_curves.h"
#include "postfx/broaden.h"

namespace vsil {
namespace {

std::vector<LineWidthSample> measureLineWidths(const cv::Mat1b& lineMask) {
  return vsil::measureLineWidths(lineMask, "test band", std::size_t(1) << 30);
}

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
    // The measurement accuracy, ±0.5 px, for the mean and the median alike (no
    // skeleton spurs pull the mean away).
    EXPECT_NEAR(stats.mean, areaWidth, 0.5) << "W " << width;
    EXPECT_NEAR(stats.median, areaWidth, 0.5) << "W " << width;
  }
}

// A line wider than what it outlines fills a region whose few medial samples read its diameter
// (round 14: 23.3 px for a 12 px line round a 14 px sphere): said, when such regions hold a
// tenth of the samples or more; a ring, and a ring beside a few dots, are lines.
TEST(LineWidth, RegionsNoLongerThanWideAreSaidNotToBeLines) {
  cv::Mat1b disc(64, 64, std::uint8_t(0));
  cv::circle(disc, {32, 32}, 12, 255, cv::FILLED);
  const std::string warning = regionsNotLinesWarning(disc, measureLineWidths(disc), "disc.png");
  EXPECT_NE(warning.find("disc.png: "), std::string::npos) << warning;
  EXPECT_NE(warning.find("samples lie in 1 region no longer than wide"), std::string::npos)
      << warning;

  cv::Mat1b ring(128, 128, std::uint8_t(0));
  cv::circle(ring, {64, 64}, 40, 255, 6);
  EXPECT_EQ(regionsNotLinesWarning(ring, measureLineWidths(ring), "ring.png"), "");
  for (int k = 0; k < 4; ++k) cv::circle(ring, {10 + 8 * k, 10}, 2, 255, cv::FILLED);
  EXPECT_EQ(regionsNotLinesWarning(ring, measureLineWidths(ring), "ring.png"), "");
}

TEST(LineWidth, AxisBandsOfEveryIntegerWidth) {
  // From 2: a one-pixel line reads 0.5 px (line_width.h, the edge smoothing's limit).
  for (int width = 2; width <= 12; ++width) {
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

// Straight bands of pixel centres within w/2 of a line, at many angles; the truth is the band's
// own area width (pixel count in a window / window length), which differs from w on lattice
// directions (whole rows).
TEST(LineWidth, StraightBandsAtManyAnglesWithinAQuarterPixel) {
  for (double width : {2.0, 3.0, 4.0, 5.0, 8.0, 13.0, 21.0}) {
    for (double angle : {0.0, 7.0, 15.0, 26.6, 33.0, 45.0, 58.0, 71.0, 90.0, 123.0, 160.0}) {
      const double a = angle * std::numbers::pi / 180, tx = std::cos(a), ty = std::sin(a);
      const cv::Point2d point(100.3, 99.6);
      cv::Mat1b band(200, 200, std::uint8_t(0));
      for (int y = 0; y < band.rows; ++y) {
        for (int x = 0; x < band.cols; ++x) {
          if (std::abs(-(x - point.x) * ty + (y - point.y) * tx) < width / 2) band(y, x) = 255;
        }
      }
      const double areaWidth = test::straightBandWidth(band, point, angle, 60, width + 4);
      std::vector<double> widths;
      for (const auto& s : measureLineWidths(band)) {
        if (std::abs((s.pixel.x - point.x) * tx + (s.pixel.y - point.y) * ty) < 60) {
          widths.push_back(s.width);
        }
      }
      const WidthStatistics stats = summarizeWidths(widths);
      // Measured: within ±0.25 px (line_width.h); the issue asks ±0.5.
      EXPECT_NEAR(stats.median, areaWidth, 0.3) << "w " << width << " at " << angle << " deg";
      EXPECT_NEAR(stats.mean, areaWidth, 0.3) << "w " << width << " at " << angle << " deg";
    }
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

// The memory the measurement needs is checked before it is taken: a solid 2048² square (its
// lines' box) needs ~710 MiB, over a 100 MiB limit; a thin line across the same image fits.
TEST(LineWidth, ALineBoxOverTheMemoryLimitIsRefused) {
  const cv::Mat1b square(2048, 2048, std::uint8_t(255));
  try {
    vsil::measureLineWidths(square, "square.png", std::size_t(100) << 20);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              "square.png: measuring lines across 2048x2048 pixels needs 710 MiB, over the "
              "--max-memory limit of 100 MiB");
  }
  cv::Mat1b line(2048, 2048, std::uint8_t(0));
  line.row(1000).setTo(255);
  line.row(1001).setTo(255);
  EXPECT_FALSE(vsil::measureLineWidths(line, "line.png", std::size_t(100) << 20).empty());
}

// A transparent render's background is black (0, 0, 0, 0): not a line of the default black.
TEST(LineWidth, TransparentPixelsAreNoLine) {
  cv::Mat4b image(8, 8, cv::Vec4b(0, 0, 0, 0));
  image(3, 4) = cv::Vec4b(0, 0, 0, 255);
  image(5, 4) = cv::Vec4b(0, 0, 0, 127);  // less than half opaque
  const cv::Mat1b mask = lineMaskFromImage(image, Rgba{0, 0, 0, 255});
  EXPECT_EQ(cv::countNonZero(mask), 1);
  EXPECT_EQ(mask(3, 4), 255);
}

// A 16-bit PNG of the same picture (v * 257) gives the same line pixels, grey, RGB and RGBA.
TEST(LineWidth, SixteenBitImagesGiveTheEightBitMask) {
  cv::Mat4b image(16, 16, cv::Vec4b(255, 255, 255, 255));
  image(3, 4) = cv::Vec4b(0, 0, 0, 255);
  image(7, 9) = cv::Vec4b(20, 30, 35, 255);    // within the tolerance of black
  image(9, 2) = cv::Vec4b(0, 0, 0, 100);       // less than half opaque
  image(12, 12) = cv::Vec4b(90, 90, 90, 255);  // too light
  cv::Mat3b bgr;
  cv::Mat1b grey;
  cv::cvtColor(image, bgr, cv::COLOR_BGRA2BGR);
  cv::cvtColor(bgr, grey, cv::COLOR_BGR2GRAY);
  for (const cv::Mat& eight : {cv::Mat(image), cv::Mat(bgr), cv::Mat(grey)}) {
    cv::Mat sixteen;
    eight.convertTo(sixteen, CV_16U, 257.0);
    const cv::Mat1b expected = lineMaskFromImage(eight, Rgba{0, 0, 0, 255});
    const cv::Mat1b got = lineMaskFromImage(sixteen, Rgba{0, 0, 0, 255});
    EXPECT_EQ(cv::countNonZero(expected != got), 0) << eight.channels() << " channels";
    EXPECT_GE(cv::countNonZero(got), 2);
  }
}

TEST(LineWidth, HistogramBinWidthBelowAHundredthIsRefused) {
  EXPECT_NO_THROW(checkHistogramBinWidth("--bin-width", 0.01));
  for (double bad : {0.0, 1e-9, -1.0, std::nan(""), double(INFINITY)}) {
    EXPECT_THROW(checkHistogramBinWidth("--bin-width", bad), InputError) << bad;
  }
}

}  // namespace
}  // namespace vsil
