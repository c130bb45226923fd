#include "postfx/line_width.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <sstream>
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>

#include "core/error.h"
#include "core/limits.h"
#include "core/options.h"

namespace vsil {
namespace {

// measureLineWidths: the fine grid's refinement, the smoothing of the edge (pixels), and how far
// below the 3x3 neighbourhood's ridge height a pixel's own block may be and still count as
// medial (fine pixels: about the height noise along a ridge).
constexpr int kWidthUpsampling = 4;
constexpr double kEdgeSigma = 0.7;
constexpr float kRidgeTolerance = 1.0f;

double percentile(const std::vector<double>& sorted, double q) {
  const double position = q * double(sorted.size() - 1);
  const auto i = std::size_t(position);
  const double f = position - double(i);
  return i + 1 < sorted.size() ? sorted[i] * (1 - f) + sorted[i + 1] * f : sorted[i];
}

std::optional<double> depthNear(const cv::Mat1f& depth, cv::Point p) {
  std::optional<double> best;
  int bestDistance = 1 << 30;
  for (int dy = -2; dy <= 2; ++dy) {
    for (int dx = -2; dx <= 2; ++dx) {
      const int x = p.x + dx, y = p.y + dy;
      if (x < 0 || y < 0 || x >= depth.cols || y >= depth.rows) continue;
      const float d = depth(y, x);
      if (std::isnan(d) || dx * dx + dy * dy >= bestDistance) continue;
      best = d;
      bestDistance = dx * dx + dy * dy;
    }
  }
  return best;
}

}  // namespace

cv::Mat1b lineMaskFromImage(const cv::Mat& given, const Rgba& lineColor, int tolerance) {
  cv::Mat image = given;
  if (given.depth() == CV_16U) given.convertTo(image, CV_8U, 1.0 / 257.0);  // 65535 -> 255
  if (image.depth() != CV_8U) {
    throw std::invalid_argument("lineMaskFromImage: 8- or 16-bit images only");
  }
  cv::Mat1b mask;
  if (image.channels() == 1) {
    const int grey = (lineColor.r * 299 + lineColor.g * 587 + lineColor.b * 114) / 1000;
    cv::inRange(image, std::max(0, grey - tolerance), std::min(255, grey + tolerance), mask);
    return mask;
  }
  cv::Mat3b bgr;
  cv::Mat1b opaque;  // at least half opaque
  if (image.channels() == 4) {
    cv::cvtColor(image, bgr, cv::COLOR_BGRA2BGR);
    cv::extractChannel(image, opaque, 3);
    opaque = opaque >= 128;
  } else {
    bgr = image;
  }
  const cv::Scalar low(std::max(0, lineColor.b - tolerance), std::max(0, lineColor.g - tolerance),
                       std::max(0, lineColor.r - tolerance));
  const cv::Scalar high(std::min(255, lineColor.b + tolerance),
                        std::min(255, lineColor.g + tolerance),
                        std::min(255, lineColor.r + tolerance));
  cv::inRange(bgr, low, high, mask);
  if (!opaque.empty()) mask &= opaque;
  return mask;
}

std::vector<LineWidthSample> measureLineWidths(const cv::Mat1b& lineMask, const std::string& where,
                                               std::size_t maxBytes) {
  if (lineMask.empty()) return {};
  // Work on the lines' bounding box plus a margin of non-line pixels (the image border counts
  // as non-line).
  cv::Rect box = cv::boundingRect(lineMask);
  std::vector<LineWidthSample> samples;
  if (box.empty()) return samples;
  const int margin = 4;  // the edge smoothing's reach plus one
  limits::checkMemory(where + ": measuring lines across " + std::to_string(box.width) + "x" +
                          std::to_string(box.height) + " pixels",
                      std::uint64_t(box.width + 2 * margin) *
                          std::uint64_t(box.height + 2 * margin) * kLineWidthBytesPerPixel,
                      maxBytes);
  cv::Mat1f coarse(box.height + 2 * margin, box.width + 2 * margin, 0.0f);
  cv::Mat1f(lineMask(box) != 0)
      .convertTo(coarse(cv::Rect(margin, margin, box.width, box.height)), CV_32F, 1.0 / 255.0);
  // The band's edge at sub-pixel resolution: the 0.5 level of the mask smoothed by a Gaussian of
  // kEdgeSigma and interpolated bilinearly, sampled on a grid kWidthUpsampling times finer. On
  // axis-aligned bands this edge lies exactly halfway between line and non-line pixel centres,
  // so the area inside it is the pixel count. On oblique bands the plain (unsmoothed) level line
  // zigzags along the pixel stairs, and a nearest-distance measure sees only its inward teeth
  // (0.4 px low at W = 21); the smoothing flattens the teeth.
  const int f = kWidthUpsampling;
  cv::Mat1f fine;
  cv::Mat1f smooth;
  cv::GaussianBlur(coarse, smooth, cv::Size(7, 7), kEdgeSigma, kEdgeSigma, cv::BORDER_CONSTANT);
  cv::resize(smooth, fine, coarse.size() * f, 0, 0, cv::INTER_LINEAR);
  const cv::Mat1b fineMask = fine >= 0.5f;
  cv::Mat1f distance;
  cv::distanceTransform(fineMask, distance, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  // Per coarse pixel, the largest fine distance inside it.
  cv::Mat1f blockMax(coarse.size(), 0.0f);
  for (int y = 0; y < fine.rows; ++y) {
    for (int x = 0; x < fine.cols; ++x) {
      float& m = blockMax(y / f, x / f);
      m = std::max(m, distance(y, x));
    }
  }
  // Medial pixels: line pixels whose block holds (within kRidgeTolerance fine pixels) the
  // largest distance of their 3x3 neighbourhood, i.e. ridge points of the distance map. Their
  // width is twice the ridge height: the largest fine distance within one pixel, which finds
  // the ridge wherever it passes between pixel centres.
  cv::Mat1f neighbourhoodMax;
  cv::dilate(blockMax, neighbourhoodMax, cv::Mat());
  for (int y = 0; y < coarse.rows; ++y) {
    for (int x = 0; x < coarse.cols; ++x) {
      if (coarse(y, x) == 0.0f) continue;
      const float height = neighbourhoodMax(y, x);
      if (blockMax(y, x) < height - kRidgeTolerance) continue;
      // The fine distance is to the nearest fine centre outside, which lies on average half a
      // fine pixel beyond the edge, while the ridge height found is on average half a fine
      // pixel below the ridge's crest: the two cancel (measured on axis bands: exact).
      const double width = 2.0 * height / f;
      samples.push_back({{x - margin + box.x, y - margin + box.y}, width});
    }
  }
  return samples;
}

void checkHistogramBinWidth(const std::string& name, double binWidth) {
  if (!(std::isfinite(binWidth) && binWidth >= kMinHistogramBinWidth)) {
    throwInputError(name + " " + formatNumber(binWidth),
                    "must be at least " + formatNumber(kMinHistogramBinWidth) + " pixels");
  }
}

WidthStatistics summarizeWidths(std::vector<double> widths, double binWidth) {
  WidthStatistics stats;
  stats.binWidth = binWidth;
  if (widths.empty()) return stats;
  std::sort(widths.begin(), widths.end());
  stats.count = int(widths.size());
  double sum = 0;
  for (double w : widths) sum += w;
  stats.mean = sum / double(widths.size());
  stats.min = widths.front();
  stats.max = widths.back();
  stats.median = percentile(widths, 0.5);
  stats.p05 = percentile(widths, 0.05);
  stats.p25 = percentile(widths, 0.25);
  stats.p75 = percentile(widths, 0.75);
  stats.p95 = percentile(widths, 0.95);
  stats.histogram.assign(std::size_t(stats.max / binWidth) + 1, 0);
  for (double w : widths) ++stats.histogram[std::size_t(w / binWidth)];
  return stats;
}

std::vector<DepthBin> widthAgainstDepth(const std::vector<LineWidthSample>& samples,
                                        const cv::Mat1f& depth, int binCount) {
  std::vector<std::vector<double>> perBin(static_cast<std::size_t>(binCount));
  for (const auto& sample : samples) {
    const auto d = depthNear(depth, sample.pixel);
    if (!d) continue;
    const int bin = std::clamp(int(*d * binCount), 0, binCount - 1);
    perBin[std::size_t(bin)].push_back(sample.width);
  }
  std::vector<DepthBin> bins;
  for (int i = 0; i < binCount; ++i) {
    DepthBin bin{double(i) / binCount, double(i + 1) / binCount};
    const WidthStatistics stats = summarizeWidths(perBin[std::size_t(i)]);
    bin.count = stats.count;
    bin.meanWidth = stats.mean;
    bin.medianWidth = stats.median;
    bins.push_back(bin);
  }
  return bins;
}

cv::Mat3b plotWidthAgainstDepth(const std::vector<LineWidthSample>& samples, const cv::Mat1f& depth,
                                const std::vector<DepthBin>& bins) {
  const int width = 640, height = 480, left = 70, right = 20, top = 30, bottom = 60;
  cv::Mat3b plot(height, width, cv::Vec3b(255, 255, 255));
  double maxWidth = 1;
  for (const auto& s : samples) maxWidth = std::max(maxWidth, s.width);
  maxWidth = std::ceil(maxWidth * 1.1);
  const auto toPixel = [&](double d, double w) {
    return cv::Point(left + int(d * (width - left - right)),
                     height - bottom - int(w / maxWidth * (height - top - bottom)));
  };
  const cv::Scalar black(0, 0, 0), grey(160, 160, 160), blue(200, 80, 0);
  const auto font = cv::FONT_HERSHEY_SIMPLEX;
  cv::line(plot, toPixel(0, 0), toPixel(1, 0), black, 1);
  cv::line(plot, toPixel(0, 0), toPixel(0, maxWidth), black, 1);
  for (int i = 0; i <= 4; ++i) {
    const double d = i / 4.0, w = maxWidth * i / 4.0;
    char text[32];
    std::snprintf(text, sizeof text, "%.2f", d);
    cv::putText(plot, text, toPixel(d, 0) + cv::Point(-15, 20), font, 0.4, black);
    std::snprintf(text, sizeof text, "%.1f", w);
    cv::putText(plot, text, toPixel(0, w) + cv::Point(-50, 5), font, 0.4, black);
  }
  cv::putText(plot, "normalized depth", {width / 2 - 60, height - 15}, font, 0.5, black);
  cv::putText(plot, "line width (px)", {5, 18}, font, 0.5, black);
  for (const auto& s : samples) {
    if (const auto d = depthNear(depth, s.pixel))
      cv::circle(plot, toPixel(*d, s.width), 1, grey, -1);
  }
  cv::Point previous(-1, -1);
  for (const auto& bin : bins) {
    if (bin.count == 0) continue;
    const cv::Point p = toPixel(0.5 * (bin.depthFrom + bin.depthTo), bin.meanWidth);
    cv::circle(plot, p, 4, blue, -1);
    if (previous.x >= 0) cv::line(plot, previous, p, blue, 2);
    previous = p;
  }
  return plot;
}

std::string emptyDepthBinsWarning(const std::vector<LineWidthSample>& samples,
                                  const std::vector<DepthBin>& bins, const std::string& where) {
  int binned = 0;
  for (const DepthBin& bin : bins) binned += bin.count;
  if (samples.empty() || binned > 0) return "";
  return where + ": none of the " + std::to_string(samples.size()) +
         " line samples has a depth within 2 px: every depth bin is empty";
}

std::string regionsNotLinesWarning(const cv::Mat1b& lineMask,
                                   const std::vector<LineWidthSample>& samples,
                                   const std::string& where) {
  if (samples.empty()) return "";
  cv::Mat1i labels;
  const int regions = cv::connectedComponents(lineMask, labels, 8, CV_32S) - 1;  // 0: background
  std::vector<int> count(std::size_t(regions) + 1, 0);
  std::vector<double> widthSum(std::size_t(regions) + 1, 0.0);
  for (const LineWidthSample& sample : samples) {
    const int region = labels(sample.pixel);
    ++count[std::size_t(region)];
    widthSum[std::size_t(region)] += sample.width;
  }
  int notLines = 0, samplesInThem = 0;
  double widest = 0;
  for (int region = 1; region <= regions; ++region) {
    const int n = count[std::size_t(region)];
    if (n == 0) continue;
    const double width = widthSum[std::size_t(region)] / n;
    if (double(n) >= width) continue;
    ++notLines;
    samplesInThem += n;
    widest = std::max(widest, width);
  }
  // Dots and short dashes of a real render hold a few percent of the samples; a region that
  // swallowed the lines holds most.
  if (samplesInThem < kNotLineShare * double(samples.size())) return "";
  std::ostringstream text;
  text << std::fixed << std::setprecision(1) << where << ": " << samplesInThem << " of "
       << samples.size() << " samples lie in " << notLines
       << (notLines == 1 ? " region" : " regions") << " no longer than wide (up to " << widest
       << " px across): filled regions, not lines (a line wider than what it outlines, or lines "
          "merged); their widths are the regions' diameters";
  return text.str();
}

nlohmann::json widthStatisticsJson(const WidthStatistics& stats) {
  return {{"count", stats.count},
          {"mean", stats.mean},
          {"median", stats.median},
          {"min", stats.min},
          {"max", stats.max},
          {"p05", stats.p05},
          {"p25", stats.p25},
          {"p75", stats.p75},
          {"p95", stats.p95},
          {"bin_width", stats.binWidth},
          {"histogram", stats.histogram}};
}

nlohmann::json depthBinsJson(const std::vector<DepthBin>& bins) {
  nlohmann::json rows = nlohmann::json::array();
  for (const DepthBin& bin : bins) {
    // An empty bin has no width: null, not a width of 0.
    const auto width = [&](double w) {
      return bin.count > 0 ? nlohmann::json(w) : nlohmann::json();
    };
    rows.push_back({{"depth_from", bin.depthFrom},
                    {"depth_to", bin.depthTo},
                    {"count", bin.count},
                    {"mean_width", width(bin.meanWidth)},
                    {"median_width", width(bin.medianWidth)}});
  }
  return rows;
}

}  // namespace vsil
