#pragma once
// How wide the broadened lines are, and the one Gaussian line model that turns a wanted width
// into the blur's sigma and a line pixel's intensity.
//
// The line model (../shared/papers/README.md, "Nagy & Klein — broadening"). A long straight
// line of mass I per unit length, blurred by a 2D Gaussian of standard deviation s, has the cross
// profile I·exp(-r²/2s²)/(√(2π)s); the threshold T cuts it at the half-width
//     r = s·sqrt(2·ln(I / (T·√(2π)·s))),   so   I(w) = T·√(2π)·s·exp(w² / (8 s²))
// gives the total width w = 2r. Two facts about one-pixel digital curves enter the model:
//  - density: the outline pixels of a footprint (a filled pixel with a non-filled 8-neighbour)
//    of an edge whose normal makes the angle φ with an axis are the pixels in a strip of width
//    |cos φ| + |sin φ| along the edge, i.e. |cos φ| + |sin φ| pixels per unit length (1 on axes,
//    √2 on diagonals). broaden.cpp divides each pixel's intensity by its locally measured
//    density, so that every line carries mass I per unit length whatever its orientation.
//  - stair steps: across the line the pixels are spread uniformly over that strip, a box of
//    width b = |cos φ| + |sin φ|, so the profile is the Gaussian convolved with the box, close to
//    a Gaussian of variance s² + b²/12; the model uses the mean of b² over all orientations,
//    1 + 2/π, so s_eff² = s² + (1 + 2/π)/12 (a residual of ±0.05/s² in variance).
// The band of pixel centres within r of the line's centre then has area 2r per unit length.
//
// Limits (documented, not hidden): a line end is a half line, with half the mass within reach,
// so ends are rounded and somewhat shorter; lines closer than about their width plus 3 s merge,
// since their blurred profiles add (dense lines thicken and fill the gaps between them); lines
// exactly along a pixel axis or diagonal can only take widths in the steps of the pixel rows
// they cover (1 px on axes, 0.71 px on diagonals): with the kernel a quarter row off-centre
// ((1/4, 1/4) near the axes, (1/4, 0) near the diagonals, see broaden.h) every row count is
// reachable, so they come out within half a row (±0.5 px, ±0.36 px) of the asked width
// (measured over all orientations in 1 degree steps: within ±0.31 px for W = 2..40);
// depth-adaptive widths follow the depth smoothed along the line over about s. The kernel
// shift does not enter the law: a shift moves a band, it does not change its area.
#include <string>

namespace vsil {

// Total line width in pixels as a function of the normalized depth d in [0, 1] (as written by
// --meta-out, View::normalizedDepth): w(d) = near + (far - near)·d. Fixed width: near == far.
struct WidthLaw {
  double near = 1.0;
  double far = 1.0;

  static WidthLaw fixed(double width) { return {width, width}; }
  static WidthLaw depthAdaptive(double nearWidth, double farWidth) { return {nearWidth, farWidth}; }
  bool isFixed() const { return near == far; }
  double maxWidth() const { return near > far ? near : far; }
  // d is clamped to [0, 1].
  double widthAt(double depth) const;
  // W == 1 everywhere: the one-pixel line itself, nothing to broaden.
  bool isIdentity() const { return near == 1.0 && far == 1.0; }
  // Throws InputError naming `flagName` when a width is below 1 or not finite.
  void validate(const std::string& flagName = "--width") const;
};

// How far out in the Gaussian's tail the widest line is cut: r_max = kTailSigmas · sigma, i.e. the
// threshold is exp(-kTailSigmas²/2) ≈ 3.4e-4 of the widest line's peak. Further out, float FFT
// round-off would begin to move band edges; closer in, thin lines in a depth-adaptive law sit too
// near their peak and lose accuracy (their width changes by sigma²·ε/r for a mass error ε).
inline constexpr double kTailSigmas = 4.0;
// Below this the stair steps of a digital line show through the blur as a wobble of the band
// edges (measured: at sigma 1 straight lines at W = 8 vary by ±0.45 px with orientation, at 2 by
// ±0.15 px).
inline constexpr double kMinimumSigma = 2.0;

// The blur's sigma for a law whose widest line is maxWidth pixels.
double blurSigmaForMaxWidth(double maxWidth);

// THE Gaussian width law: the intensity a line must carry, per unit length, for the band
// "blurred ≥ kLineThreshold" to be `width` pixels wide after a blur by `sigma`.
inline constexpr double kLineThreshold = 1.0;
double lineIntensityForWidth(double width, double sigma);

// Its inverse (by bisection on lineIntensityForWidth, so the law lives in one place).
double lineWidthForIntensity(double intensity, double sigma);

}  // namespace vsil
