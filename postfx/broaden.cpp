#include "postfx/broaden.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

namespace vsil {
namespace {

// A density below this is a line end or an isolated pixel; ends get at most twice a line's
// intensity per pixel, which gives back the half of the mass they miss.
constexpr double kMinimumDensity = 0.5;

}  // namespace

cv::Mat1f lineDensity(const cv::Mat1b& lineMask) {
  cv::Mat1f mask;
  cv::Mat1b binary = lineMask != 0;
  binary.convertTo(mask, CV_32F, 1.0 / 255.0);
  const double s = kDensityScale;
  const int reach = int(std::ceil(4 * s));
  cv::Mat1f blurred;
  cv::GaussianBlur(mask, blurred, cv::Size(2 * reach + 1, 2 * reach + 1), s, s,
                   cv::BORDER_CONSTANT);
  // A straight line of unit density blurs to 1/(√(2π)s) at its centre; the pixels of a digital
  // line lie across a strip of width b, which lowers the mean of 1/estimate by b²/(12 s²), b²
  // averaged over orientations as in width_law.h.
  const double stripBias = 1.0 - (1.0 + 2.0 / std::numbers::pi) / (12.0 * s * s);
  return blurred * (std::sqrt(2.0 * std::numbers::pi) * s / stripBias);
}

cv::Mat1f diagonalShare(const cv::Mat1b& lineMask, const cv::Mat1f& density) {
  CV_Assert(lineMask.size() == density.size());
  cv::Mat1f share(lineMask.size(), 0.0f);
  const int lastX = lineMask.cols - 1, lastY = lineMask.rows - 1;
  const double full = std::cos(2 * kDiagonalFullDegrees * std::numbers::pi / 180.0);
  const double none = std::cos(2 * kDiagonalNoneDegrees * std::numbers::pi / 180.0);
  for (int y = 0; y < lineMask.rows; ++y) {
    const int ym = std::max(y - 1, 0), yp = std::min(y + 1, lastY);
    for (int x = 0; x < lineMask.cols; ++x) {
      if (!lineMask(y, x)) continue;
      const int xm = std::max(x - 1, 0), xp = std::min(x + 1, lastX);
      // Central differences (border pixels repeated), in double.
      const double m = density(y, x);
      const double a = double(density(y, xp)) - 2 * m + double(density(y, xm));
      const double c = double(density(yp, x)) - 2 * m + double(density(ym, x));
      const double b = 0.25 * (double(density(yp, xp)) - double(density(yp, xm)) -
                               double(density(ym, xp)) + double(density(ym, xm)));
      const double norm = std::sqrt((a - c) * (a - c) + 4 * b * b);
      if (!(norm > 0)) continue;
      const double cos2Delta = std::abs(2 * b) / norm;  // 1 on a diagonal, 0 on an axis
      const double t = std::clamp((cos2Delta - none) / (full - none), 0.0, 1.0);
      share(y, x) = float(t * t * (3 - 2 * t));
    }
  }
  return share;
}

namespace {

// One side of the region broadenLines works on: at least `needed` pixels, rounded up to the
// next of 64, 96, 128, 192, 256, 384, ... (at most the image's side), so that the FFT sizes of
// consecutive frames repeat and their plans and kernel spectra are reused.
int roundedSide(int needed, int imageSide) {
  int side = 64;
  while (side < needed) side = side % 3 == 0 ? side / 3 * 4 : side / 2 * 3;
  return std::min(side, imageSide);
}

// [begin, begin + length) covering [lo, hi), kept inside [0, imageSide).
std::pair<int, int> placedRange(int lo, int hi, int length, int imageSide) {
  const int begin = std::clamp(lo - (length - (hi - lo)) / 2, 0, imageSide - length);
  return {begin, length};
}

}  // namespace

cv::Mat1b broadenLines(const cv::Mat1f& lineWidths, FftGaussianBlur& blur, double maxWidth) {
  if (lineWidths.empty()) throw std::invalid_argument("broadenLines: empty image");
  const cv::Mat1b lineMask = lineWidths > 0;
  if (maxWidth <= 0) cv::minMaxLoc(lineWidths, nullptr, &maxWidth);
  if (maxWidth <= 1.0) return lineMask;  // W = 1: the one-pixel lines themselves
  const cv::Rect lines = cv::boundingRect(lineMask);
  if (lines.empty()) return lineMask;

  // The band reaches at most the blur's reach beyond the lines, and the density and the
  // diagonal share need the lines' neighbourhood: work on the lines' bounding box grown by the
  // blur's reach plus one pixel, rounded to a few sizes. Outside it the band is empty.
  const double sigma = blurSigmaForMaxWidth(maxWidth);
  const int margin = gaussianReach(sigma, kBroadeningKernelShift) + 1;
  const cv::Rect grown = (lines + cv::Point(-margin, -margin) + cv::Size(2 * margin, 2 * margin)) &
                         cv::Rect(0, 0, lineWidths.cols, lineWidths.rows);
  const auto [x0, width] = placedRange(grown.x, grown.br().x,
                                       roundedSide(grown.width, lineWidths.cols), lineWidths.cols);
  const auto [y0, height] = placedRange(
      grown.y, grown.br().y, roundedSide(grown.height, lineWidths.rows), lineWidths.rows);
  const cv::Rect region(x0, y0, width, height);
  const cv::Mat1f widths = lineWidths(region);
  const cv::Mat1b mask = lineMask(region);

  const cv::Mat1f density = lineDensity(mask);
  cv::Mat1f intensity(widths.size(), 0.0f);
  for (int y = 0; y < widths.rows; ++y) {
    for (int x = 0; x < widths.cols; ++x) {
      const float width = widths(y, x);
      if (!(width > 0)) continue;
      const double perLength = lineIntensityForWidth(std::max(1.0f, width), sigma);
      intensity(y, x) = float(perLength / std::max(kMinimumDensity, double(density(y, x))));
    }
  }
  // The diagonal kernel's part of the intensity (broaden.h); blurSum adds the two blurs.
  const cv::Mat1f share = diagonalShare(mask, density);
  cv::Mat1f blurred;
  if (cv::countNonZero(share) == 0) {
    blurred = blur.blur(intensity, sigma, kBroadeningKernelShift);
  } else {
    const cv::Mat1f diagonal = intensity.mul(share);
    const cv::Mat1f axis = intensity - diagonal;
    const FftGaussianBlur::ShiftedImage parts[] = {{&axis, kBroadeningKernelShift},
                                                   {&diagonal, kDiagonalKernelShift}};
    blurred = blur.blurSum(parts, sigma);
  }
  cv::Mat1b band = lineMask.clone();
  cv::Mat1b bandInRegion = band(region);  // a view into band
  bandInRegion |= blurred >= float(kLineThreshold);
  return band;
}

cv::Mat1b broadenMask(const cv::Mat1b& lineMask, double width, FftGaussianBlur& blur) {
  WidthLaw::fixed(width).validate();
  cv::Mat1f widths(lineMask.size(), 0.0f);
  widths.setTo(float(width), lineMask != 0);
  return broadenLines(widths, blur, width);
}

cv::Mat1f lineWidthsFromDepth(const cv::Mat1b& lineMask, const cv::Mat1f& depth,
                              const WidthLaw& law) {
  if (lineMask.size() != depth.size()) {
    throw std::invalid_argument("lineWidthsFromDepth: mask and depth differ in size");
  }
  cv::Mat1f widths(lineMask.size(), 0.0f);
  if (law.isFixed()) {  // every line pixel the same width: no per-pixel depth needed
    widths.setTo(float(law.widthAt(0.0)), lineMask);
    return widths;
  }
  for (int y = 0; y < lineMask.rows; ++y) {
    for (int x = 0; x < lineMask.cols; ++x) {
      if (!lineMask(y, x)) continue;
      const float d = depth(y, x);
      widths(y, x) = float(law.widthAt(std::isnan(d) ? 0.0 : double(d)));
    }
  }
  return widths;
}

cv::Mat1b broadenSilhouettes(const FrameBuffers& frame, const WidthLaw& law,
                             FftGaussianBlur& blur) {
  law.validate();
  const cv::Mat1b silhouettes = frame.state == std::uint8_t(PixelState::Silhouette);
  cv::Mat1f depth = frame.depth;
  if (depth.empty()) depth = cv::Mat1f(frame.state.size(), 0.0f);
  return broadenLines(lineWidthsFromDepth(silhouettes, depth, law), blur, law.maxWidth());
}

}  // namespace vsil
