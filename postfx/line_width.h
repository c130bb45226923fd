#pragma once
// Line-width measurement on finished images (vsil measure-width). The width at a point of a
// line's centre is the sum of its distances to the two sides: per medial-axis pixel p (the
// morphological skeleton of the line mask), DT(p) + DT(p + n), where DT is OpenCV's exact
// Euclidean distance to the nearest non-line pixel centre and n the unit step away from that
// nearest pixel. On a band whose centre falls on p this is 2·DT(p) - 1 + 1 = the number of
// pixels across; when the centre falls between two pixels the far sample supplies the missing
// half pixel, so even and odd widths are both measured exactly on axis-aligned bands. On oblique
// lines the nearest non-line pixel centre lies a little farther than the band edge, and the
// estimate reads low by 0.3-0.6 px (measured on broadened circles, tests/postfx/line_width_test).
#include <optional>
#include <vector>

#include <opencv2/core.hpp>

#include "postfx/color.h"

namespace vsil {

struct LineWidthSample {
  cv::Point pixel;  // a medial-axis pixel
  double width;     // pixels
};

struct WidthStatistics {
  int count = 0;
  double mean = 0, median = 0, min = 0, max = 0;
  double p05 = 0, p25 = 0, p75 = 0, p95 = 0;
  double binWidth = 1.0;
  std::vector<int> histogram;  // bin i counts widths in [i·binWidth, (i+1)·binWidth)
};

struct DepthBin {
  double depthFrom = 0, depthTo = 0;
  int count = 0;
  double meanWidth = 0, medianWidth = 0;
};

// Line pixels: those within `tolerance` (per channel, 0..255) of `lineColor`; grey images compare
// with the colour's grey value. Alpha is ignored.
cv::Mat1b lineMaskFromImage(const cv::Mat& image, const Rgba& lineColor, int tolerance = 40);

std::vector<LineWidthSample> measureLineWidths(const cv::Mat1b& lineMask);

WidthStatistics summarizeWidths(std::vector<double> widths, double binWidth = 1.0);

// Depth image: 32-bit float (NaN = nothing), 16-bit (v/65535) or 8-bit (v/255). A sample takes the
// depth of the nearest pixel within 2 px that has one; samples without are left out.
std::vector<DepthBin> widthAgainstDepth(const std::vector<LineWidthSample>& samples,
                                        const cv::Mat& depthImage, int binCount = 10);

// Scatter of width against depth (points) with the bins' means (line), axes and labels.
cv::Mat3b plotWidthAgainstDepth(const std::vector<LineWidthSample>& samples,
                                const cv::Mat& depthImage, const std::vector<DepthBin>& bins);

}  // namespace vsil
