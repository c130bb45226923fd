#pragma once
// Broadening: one-pixel lines to lines of a chosen width (Nagy–Klein). Each line pixel gets an
// intensity from the Gaussian width law (width_law.h), divided by the local pixel density of its
// line; the image is blurred by one Gaussian through the FFT (gaussian_fft.h) and thresholded
// once. The result is a bi-level mask (255 = line).
//
// The blur kernel is centred a quarter pixel right and down of each pixel, (+1/4, +1/4). A band
// centred on a pixel row covers an odd number of rows; centred a quarter pixel off, it covers
// exactly W rows for every integer W, so lines along the pixel axes get their asked integer
// widths (and non-integer widths within ±0.5 px) instead of the nearest odd number. Lines along
// the diagonals still step by 0.71 px (one diagonal row). The whole broadened image therefore
// sits 0.35 px from the one-pixel lines, well below the half pixel by which a footprint's outline
// pixels already sit inside the true surface.
#include <opencv2/core.hpp>

#include "core/frame.h"
#include "postfx/gaussian_fft.h"
#include "postfx/width_law.h"

namespace vsil {

inline const cv::Point2d kBroadeningKernelShift{0.25, 0.25};

// Scale (pixels) over which the pixel density of a line is measured: large enough to average
// stair steps and make the estimate's bias across the strip small (±0.3 % after correction),
// small enough that lines farther apart than about 3 times this do not see each other.
inline constexpr double kDensityScale = 2.5;

// Pixels per unit length of the lines through each pixel of `lineMask` (non-zero = line),
// measured as √(2π)·s·(G_s ⊗ mask) with s = kDensityScale and corrected for the strip's width
// (width_law.h). 1 for a line along an axis, √2 along a diagonal, about 0.5 at a line's end.
cv::Mat1f lineDensity(const cv::Mat1b& lineMask);

// The general form: lineWidths holds, per pixel, the total width wanted for the line through it
// (≤ 0: not a line pixel; values in [0, 1) count as 1). sigma follows maxWidth (0: the largest
// width in the image), so a sweep can keep one sigma for several images. Line pixels are always
// part of the result (a line never disappears).
cv::Mat1b broadenLines(const cv::Mat1f& lineWidths, FftGaussianBlur& blur, double maxWidth = 0);

// Any grey or colour-less image: line pixels are the non-zero pixels of `lineMask`, all
// broadened to `width`.
cv::Mat1b broadenMask(const cv::Mat1b& lineMask, double width, FftGaussianBlur& blur);

// Widths per pixel from a depth image: w(d) of `law` where lineMask is set, 0 elsewhere.
// depth NaN on a line pixel counts as d = 0.
cv::Mat1f lineWidthsFromDepth(const cv::Mat1b& lineMask, const cv::Mat1f& depth,
                              const WidthLaw& law);

// A render's silhouettes (state == Silhouette) broadened by `law` at their depths.
cv::Mat1b broadenSilhouettes(const FrameBuffers& frame, const WidthLaw& law, FftGaussianBlur& blur);

}  // namespace vsil
