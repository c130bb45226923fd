#pragma once
// Summary of one case's frame times: median, min and max over the timed frames.
#include <optional>
#include <string>
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

// A case's timed frames, with the words that name it in a note ("bonsai 512² mip").
struct CaseFrames {
  std::string name;
  std::vector<double> ms;
};
// The spread of one case's frame times (slowest over fastest) past which a table's frame rates
// are not to be trusted. With nothing else running the cases of nk3, dv1 and illustrate kept
// within 1.05-1.56 (the orbit's views differ, llvmpipe's threads are scheduled unevenly); a
// loaded machine's swung 2x and more (README, "Ratios from paired frames").
inline constexpr double kUnsteadySpread = 2.0;
// ... and by more than this many milliseconds: frames of a few milliseconds (64² images) swing
// by 2x from the scheduler alone.
inline constexpr double kUnsteadyMs = 5.0;
// For a table whose cases' frame times spread past kUnsteadySpread and kUnsteadyMs (a case of
// at least two frames), the note that says so: the machine's speed changed during the run (other
// load, frequency scaling), so its frame rates may be off by as much; nullopt when every case was
// steadier.
std::optional<std::string> unsteadyNote(const std::vector<CaseFrames>& cases);

// CPU time of the whole process so far, in ms (every llvmpipe thread): a frame's difference is
// steadier than its wall time on a loaded machine, since it counts work, not waiting.
double processCpuMs();

}  // namespace vsil::bench
