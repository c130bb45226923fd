#include "harness/timing_stats.h"

#include <time.h>

#include <algorithm>

namespace vsil::bench {

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const std::size_t middle = values.size() / 2;
  return values.size() % 2 == 1 ? values[middle] : 0.5 * (values[middle - 1] + values[middle]);
}

TimingStats summarize(const std::vector<double>& milliseconds) {
  TimingStats stats;
  stats.frames = int(milliseconds.size());
  if (milliseconds.empty()) return stats;
  const auto [lowest, highest] = std::minmax_element(milliseconds.begin(), milliseconds.end());
  stats.msMin = *lowest;
  stats.msMax = *highest;
  stats.msMedian = median(milliseconds);
  return stats;
}

double processCpuMs() {
  timespec now{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
  return double(now.tv_sec) * 1e3 + double(now.tv_nsec) * 1e-6;
}

}  // namespace vsil::bench
