#pragma once
// Line-width measurement on finished images (vsil measure-width). The width at a point of a
// line's centre is twice its distance to the line's edge, sampled on the medial axis:
//  - edge: the 0.5 level of the line mask smoothed by a Gaussian of 0.7 px, bilinearly
//    interpolated on a 4x finer grid (exactly halfway between line and non-line pixel centres on
//    axis bands; the smoothing flattens the pixel stairs of oblique edges, whose inward teeth
//    would otherwise make a nearest-distance measure read low);
//  - distance: OpenCV's exact Euclidean transform (DIST_L2, DIST_MASK_PRECISE) on that grid;
//  - medial axis: the ridge of the distance map, one sample per line pixel whose own area holds
//    (within 1/4 px) the largest distance of its 3x3 neighbourhood; its width is twice that
//    largest distance, so the ridge is found wherever it passes between pixel centres and no
//    skeleton spurs enter the statistics.
// Measured on straight bands of known area width at 10 angles (tests/postfx/line_width_test):
// within ±0.25 px for widths 2..21, exact on axis-aligned bands. Limits: one-pixel lines
// (W = 1) read 0.5 px (the smoothing thins them), line ends and junctions give their own
// (smaller, larger) values, and the image border counts as outside.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>
#include <opencv2/core.hpp>

#include "core/color.h"

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
// with the colour's grey value; 16-bit images compare at 8 bits (a value v as v/257, rounded). In
// images with alpha, pixels less than half opaque are background whatever their colour (a
// transparent render's background is black, the default line colour).
cv::Mat1b lineMaskFromImage(const cv::Mat& image, const Rgba& lineColor, int tolerance = 40);

// What measureLineWidths holds at its peak per pixel of the lines' bounding box (and its 4-pixel
// margin): on the 4x finer grid (16 fine pixels) the smoothed mask, the binary mask, the
// distances and OpenCV's buffers for the transform, about 11 bytes each (a solid 2048² square
// measured 156 bytes per pixel).
inline constexpr std::size_t kLineWidthBytesPerPixel = 176;

// One sample per medial pixel of the non-zero pixels of lineMask. Throws InputError "<where>:
// measuring lines across WxH pixels needs N MiB, over the --max-memory limit of M MiB" when
// the lines' bounding box needs more than `maxBytes`.
std::vector<LineWidthSample> measureLineWidths(const cv::Mat1b& lineMask, const std::string& where,
                                               std::size_t maxBytes);

// The narrowest histogram bin: widths are measured to about 0.05 px, and a narrower bin only
// makes the histogram longer (1e-9 asked for billions of bins).
inline constexpr double kMinHistogramBinWidth = 0.01;
// Throws InputError naming `name` unless binWidth is finite and at least kMinHistogramBinWidth.
void checkHistogramBinWidth(const std::string& name, double binWidth);

WidthStatistics summarizeWidths(std::vector<double> widths, double binWidth = 1.0);

// `depth`: normalized depth per pixel, NaN where a pixel has none (core/depth_image.h decodes
// `render --depth-out`). A sample takes the depth of the nearest pixel within 2 px that has one;
// samples without are left out.
std::vector<DepthBin> widthAgainstDepth(const std::vector<LineWidthSample>& samples,
                                        const cv::Mat1f& depth, int binCount = 10);

// What to warn when there are samples but none has a depth (every bin empty: a depth image of
// another render, or one holding no depth), naming `where`; "" otherwise.
std::string emptyDepthBinsWarning(const std::vector<LineWidthSample>& samples,
                                  const std::vector<DepthBin>& bins, const std::string& where);

// What to warn when at least kNotLineShare of the samples lie in line regions (8-connected
// regions of lineMask) no longer than they are wide, fewer samples along their medial axis than
// their mean width: filled regions, whose widths are the region's diameter, not a line's (a
// line wider than the object it outlines, or lines merged into one area; round 14: a 12 px
// line around a 14 px sphere read 23.3 px from 3 samples); "" otherwise. A line of width W and
// length L has about L samples. Renders of the classic datasets at W = 2..8 hold a few such
// regions (dots, short dashes) with 0-2 % of the samples.
inline constexpr double kNotLineShare = 0.1;
std::string regionsNotLinesWarning(const cv::Mat1b& lineMask,
                                   const std::vector<LineWidthSample>& samples,
                                   const std::string& where);

// The report's parts as `vsil measure-width --json` writes them and vsil.measure_width returns
// them: {"count", "mean", ..., "histogram"} and [{"depth_from", "depth_to", "count",
// "mean_width", "median_width"}, ...], the widths null in a bin without samples.
nlohmann::json widthStatisticsJson(const WidthStatistics& stats);
nlohmann::json depthBinsJson(const std::vector<DepthBin>& bins);

// Scatter of width against depth (points) with the bins' means (line), axes and labels.
cv::Mat3b plotWidthAgainstDepth(const std::vector<LineWidthSample>& samples, const cv::Mat1f& depth,
                                const std::vector<DepthBin>& bins);

}  // namespace vsil
