#include "harness/timing_stats.h"

#include <time.h>

#include <algorithm>
#include <limits>

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

double pairedRatio(const std::vector<double>& a, const std::vector<double>& b) {
  const double none = std::numeric_limits<double>::quiet_NaN();
  if (a.empty() || a.size() != b.size()) return none;
  std::vector<double> quotients;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (!(a[i] > 0) || !(b[i] > 0)) return none;
    quotients.push_back(a[i] / b[i]);
  }
  return median(std::move(quotients));
}

double processCpuMs() {
  timespec now{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
  return double(now.tv_sec) * 1e3 + double(now.tv_nsec) * 1e-6;
}

}  // namespace vsil::bench
