#pragma once
// Summary of one case's frame times: median, min and max over the timed frames.
#include <vector>

namespace vsil::bench {

struct TimingStats {
  int frames = 0;
  double msMedian = 0;
  double msMin = 0;
  double msMax = 0;
  double fps() const { return msMedian > 0 ? 1000.0 / msMedian : 0.0; }
};

// The median of an even count is the mean of the two middle values. Empty input gives zeros.
double median(std::vector<double> values);
TimingStats summarize(const std::vector<double>& milliseconds);

// CPU time of the whole process so far, in ms (every llvmpipe thread): a frame's difference is
// steadier than its wall time on a loaded machine, since it counts work, not waiting.
double processCpuMs();

}  // namespace vsil::bench
