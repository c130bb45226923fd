#include "postfx/width_law.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

#include "core/error.h"

namespace vsil {
namespace {

// Variance the stair-stepped strip of a digital line adds across it, averaged over orientation:
// b²/12 for a box of width b = |cos φ| + |sin φ|, and mean(b²) = 1 + 2/π.
constexpr double kStripVariance = (1.0 + 2.0 / std::numbers::pi) / 12.0;

}  // namespace

double WidthLaw::widthAt(double depth) const {
  const double d = std::clamp(depth, 0.0, 1.0);
  return near + (far - near) * d;
}

void WidthLaw::validate(const std::string& flagName) const {
  for (double w : {near, far}) {
    if (!std::isfinite(w) || w < 1.0) {
      std::ostringstream what;
      what << "line width must be a number >= 1 pixel, got " << w;
      throwInputError(flagName, what.str());
    }
  }
}

double blurSigmaForMaxWidth(double maxWidth) {
  return std::max(kMinimumSigma, 0.5 * maxWidth / kTailSigmas);
}

double lineIntensityForWidth(double width, double sigma) {
  const double effectiveSigma = std::sqrt(sigma * sigma + kStripVariance);
  const double halfWidth = 0.5 * width;
  return kLineThreshold * std::sqrt(2.0 * std::numbers::pi) * effectiveSigma *
         std::exp(halfWidth * halfWidth / (2.0 * effectiveSigma * effectiveSigma));
}

double lineWidthForIntensity(double intensity, double sigma) {
  if (intensity <= lineIntensityForWidth(0.0, sigma)) return 0.0;
  double low = 0.0, high = 1.0;
  while (lineIntensityForWidth(high, sigma) < intensity) high *= 2.0;
  for (int i = 0; i < 100; ++i) {
    const double mid = 0.5 * (low + high);
    (lineIntensityForWidth(mid, sigma) < intensity ? low : high) = mid;
  }
  return 0.5 * (low + high);
}

}  // namespace vsil
