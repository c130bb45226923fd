#pragma once
// One progress line on stderr while a table runs: "[3/20] bonsai 512² ops frame 4/10". On a
// terminal the line is rewritten in place (\r) and erased at the end; otherwise each case gets
// one line when it starts, so logs stay readable.
#include <ostream>
#include <string>

namespace vsil::bench {

class Progress {
 public:
  Progress(std::ostream& out, bool terminal) : out_(out), terminal_(terminal) {}
  ~Progress() { finish(); }
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  void setTotalCases(int total) { total_ = total; }
  // A new case (counted): `label` like "bonsai 512² ops".
  void startCase(const std::string& label);
  // Within the current case, e.g. "warm-up 1/2" or "frame 4/10".
  void step(const std::string& what);
  // Erases the line (terminal) so that the table can be printed.
  void finish();

 private:
  void show(const std::string& text);

  std::ostream& out_;
  bool terminal_;
  int total_ = 0;
  int current_ = 0;
  std::string label_;
  std::size_t shownWidth_ = 0;
};

}  // namespace vsil::bench
