#pragma once
// Wall time for timings (metadata, progress, benchmarks): milliseconds on the steady clock.
#include <chrono>

namespace vsil {

inline double millisecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

}  // namespace vsil
