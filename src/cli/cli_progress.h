#pragma once
// A progress line on stderr for loading that takes more than a second; quiet for fast loads.
// On a terminal the line is rewritten in place ("vsil: reading bonsai.vti 45%") and erased when
// done (or when an error ends the run); elsewhere (logs, pipes) each step that is still running
// after the first second gets one line ("vsil: reading bonsai.vti ...").
#include <chrono>
#include <cstdint>
#include <functional>
#include <string>

namespace vsil::cli {

// How progressText names what is counted and its rate: {"frame", "fps"}, {"task", "tasks/s"}.
struct ProgressUnit {
  const char* noun;
  const char* rate;
};

// The progress of a run of `total` like things, for ProgressLine-style lines (animate, sweep):
// "task 37/100 [#######             ] 1 failed, 12.3 tasks/s, 5 s left", `note` ("1 failed,")
// after the bar, the rate and time left once something is done.
std::string progressText(int done, int total, double seconds, ProgressUnit unit,
                         const std::string& note = {});

class ProgressLine {
 public:
  explicit ProgressLine(std::string what);
  ~ProgressLine() { finish(); }
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;

  // For LoadOptions::progress: bytes done of total.
  std::function<void(std::uint64_t done, std::uint64_t total)> callback();
  // A new step without a fraction, e.g. "uploading the volume", shown if the line shows.
  void step(const std::string& what);
  // Erases the line (terminal).
  void finish();

 private:
  void show(const std::string& text);

  std::string what_;
  std::chrono::steady_clock::time_point start_;
  bool terminal_;
  std::string announced_;  // not a terminal: the step last written
  std::size_t shownWidth_ = 0;
  int shownPercent_ = -1;
};

}  // namespace vsil::cli
