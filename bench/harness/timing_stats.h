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
// The median over frames i of a[i] / b[i], for two cases whose frames were taken in turns (frame
// i of each in the same round, as the tables run them): a drift of the machine's speed over the
// run falls on both frames of a round and cancels in their quotient. On the 2-core machine its
// spread between runs was about half that of median(a) / median(b) where rounds are short (dv1)
// and the same where they last seconds (illustrate) (README, "Ratios from paired frames"). NaN when
// the counts differ, there are none, or a time is not positive.
double pairedRatio(const std::vector<double>& a, const std::vector<double>& b);

// CPU time of the whole process so far, in ms (every llvmpipe thread): a frame's difference is
// steadier than its wall time on a loaded machine, since it counts work, not waiting.
double processCpuMs();

}  // namespace vsil::bench
