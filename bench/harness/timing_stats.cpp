#include "harness/timing_stats.h"

#include <time.h>

#include <algorithm>
#include <cstdio>
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

std::optional<std::string> unsteadyNote(const std::vector<CaseFrames>& cases) {
  const CaseFrames* worst = nullptr;
  double worstSpread = 0;
  int over = 0, counted = 0;
  for (const CaseFrames& c : cases) {
    if (c.ms.size() < 2) continue;
    const auto [fastest, slowest] = std::minmax_element(c.ms.begin(), c.ms.end());
    if (!(*fastest > 0)) continue;
    ++counted;
    if (*slowest - *fastest <= kUnsteadyMs) continue;  // the scheduler's swing, not the machine's
    const double spread = *slowest / *fastest;
    if (spread > kUnsteadySpread) ++over;
    if (spread > worstSpread) {
      worstSpread = spread;
      worst = &c;
    }
  }
  if (over == 0) return std::nullopt;
  const auto [fastest, slowest] = std::minmax_element(worst->ms.begin(), worst->ms.end());
  char text[512];
  std::snprintf(text, sizeof text,
                "UNSTEADY RUN: frame times of one case spread up to %.2fx (%s: %.1f to %.1f ms; "
                "%d of %d cases past %.1fx): the machine's speed changed during the run (other "
                "load?), so these frame rates may be off by as much; the paired ratios cancel "
                "most of it; rerun on a quiet machine or with more --frames",
                worstSpread, worst->name.c_str(), *fastest, *slowest, over, counted,
                kUnsteadySpread);
  return std::string(text);
}

double processCpuMs() {
  timespec now{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
  return double(now.tv_sec) * 1e3 + double(now.tv_nsec) * 1e-6;
}

}  // namespace vsil::bench
