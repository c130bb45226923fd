#pragma once
// The progress of a table on stderr: "[3/20] bonsai 512² ops frame 4/10", through the shared
// ProgressLine (core/progress_line.h): rewritten in place on a terminal and erased at the end;
// otherwise each case gets one line when it starts.
#include <ostream>
#include <string>

#include "core/progress_line.h"

namespace vsil::bench {

class Progress {
 public:
  Progress(std::ostream& out, bool terminal) : line_(out, terminal) {}
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  void setTotalCases(int total) { total_ = total; }
  // A new case (counted): `label` like "bonsai 512² ops".
  void startCase(const std::string& label);
  // Within the current case, e.g. "warm-up 1/2" or "frame 4/10".
  void step(const std::string& what);
  // Erases the line (terminal) so that the table can be printed.
  void finish() { line_.finish(); }

 private:
  std::string counter() const;

  ProgressLine line_;
  int total_ = 0;
  int current_ = 0;
  std::string label_;
};

}  // namespace vsil::bench
