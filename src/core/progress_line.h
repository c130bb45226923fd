#pragma once
// One progress line on a stream (stderr) while something long runs. On a terminal the line is
// rewritten in place (\r) and erased at the end; otherwise only milestones are written, one
// line each, so that logs stay readable. `vsil bench` (its cases) and `vsil animate` (its
// frames) say what they are doing through it.
#include <cstddef>
#include <ostream>
#include <string>

namespace vsil {

class ProgressLine {
 public:
  ProgressLine(std::ostream& out, bool terminal) : out_(out), terminal_(terminal) {}
  ~ProgressLine() { finish(); }
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;

  bool terminal() const { return terminal_; }
  // Passing news: shown on a terminal, dropped from logs.
  void update(const std::string& text);
  // A milestone: shown on a terminal, one line in logs.
  void milestone(const std::string& text);
  // Erases the line (terminal), so that what follows starts on a clean line.
  void finish();

 private:
  void show(const std::string& text);

  std::ostream& out_;
  bool terminal_;
  std::size_t shownWidth_ = 0;
};

}  // namespace vsil
