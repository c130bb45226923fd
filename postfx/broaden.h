#pragma once
// Broadening: one-pixel lines to lines of a chosen width (Nagy–Klein). Each line pixel gets an
// intensity from the Gaussian width law (width_law.h), divided by the local pixel density of its
// line; the image is blurred by one Gaussian through the FFT (gaussian_fft.h) and thresholded
// once. The result is a bi-level mask (255 = line).
//
// Sub-pixel kernel shifts. A band centred on a row of pixels covers an odd number of rows, one
// centred halfway between two rows an even number: either way its width steps by two rows. Lines
// along the pixel axes sit on a row (the one-pixel line itself); lines along a pixel diagonal
// sit halfway between two diagonal rows (their outline is two diagonal rows wide). A kernel
// centred a quarter row off either gives the band every row count, so an integer width W comes
// out exactly W rows wide on an axis. No single shift does that for all four lattice directions
// at once: a shift (sx, sy) moves a band across by sx, sy (axes) and (sx ∓ sy)/√2 (diagonals),
// which would need sx, sy and sx ± sy all ≡ 1/4 modulo 1/2. Hence two kernels:
//  - kBroadeningKernelShift (+1/4, +1/4): a quarter pixel across both axes;
//  - kDiagonalKernelShift (+1/4, 0): a quarter diagonal row (0.18 px) across both diagonals.
// Each line pixel's intensity is split between the two by diagonalShare() (1 on lines within
// kDiagonalFullDegrees of a diagonal, 0 beyond kDiagonalNoneDegrees), the two images are blurred
// and summed in the spectrum (FftGaussianBlur::blurSum: one more forward transform, only when
// some pixel has a diagonal share) and thresholded once. Both shifts keep the band within 0.35 px
// of the one-pixel lines, well below the half pixel by which a footprint's outline pixels already
// sit inside the true surface; the band of a curve drifts by at most 1/4 px where its share
// changes.
#include <opencv2/core.hpp>

#include "core/frame.h"
#include "postfx/gaussian_fft.h"
#include "postfx/width_law.h"

namespace vsil {

inline const cv::Point2d kBroadeningKernelShift{0.25, 0.25};
inline const cv::Point2d kDiagonalKernelShift{0.25, 0.0};
// Angles (degrees) between a line and the nearest pixel diagonal up to which it is blurred by the
// diagonal kernel only, and from which on by the axis kernel only (smoothstep between). Lines a
// few degrees off a diagonal are made of exact diagonal runs several blur widths long, so they
// need the diagonal kernel as much as the exact diagonal; the axis kernel must take over before
// the lattice direction (1, 2) at 18.4 degrees, which the diagonal kernel leaves symmetric.
inline constexpr double kDiagonalFullDegrees = 8.0;
inline constexpr double kDiagonalNoneDegrees = 16.0;

// Scale (pixels) over which the pixel density of a line is measured: large enough to average
// stair steps and make the estimate's bias across the strip small (±0.3 % after correction),
// small enough that lines farther apart than about 3 times this do not see each other.
inline constexpr double kDensityScale = 2.5;

// Pixels per unit length of the lines through each pixel of `lineMask` (non-zero = line),
// measured as √(2π)·s·(G_s ⊗ mask) with s = kDensityScale and corrected for the strip's width
// (width_law.h). 1 for a line along an axis, √2 along a diagonal, about 0.5 at a line's end.
cv::Mat1f lineDensity(const cv::Mat1b& lineMask);

// Per line pixel of `lineMask`, the share of its intensity blurred with kDiagonalKernelShift
// (0 elsewhere). The line's local direction comes from the Hessian of `density` (lineDensity of
// the same mask, a ridge along each line): with H = [a b; b c] at the pixel, the angle Δ between
// the line and the nearest diagonal has cos 2Δ = |2b| / √((a − c)² + 4b²). Where H is zero (no
// ridge to speak of) the share is 0.
cv::Mat1f diagonalShare(const cv::Mat1b& lineMask, const cv::Mat1f& density);

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
