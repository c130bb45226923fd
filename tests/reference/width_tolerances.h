#pragma once
// The accuracy the line-width requirement asks for, shared by the CPU and GL width tests.
#include <algorithm>

namespace vsil::test {

// A long, smooth line of asked width W: within ±0.5 px or ±4 %, whichever is larger.
inline double widthTolerance(double width) {
  return std::max(0.5, 0.04 * width);
}

// Depth-adaptive widths, at the depth of each line: within ±0.75 px or ±6 %.
inline double depthTolerance(double width) {
  return std::max(0.75, 0.06 * width);
}

}  // namespace vsil::test
