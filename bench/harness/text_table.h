#pragma once
// A table of strings printed two ways: aligned plain text (for stdout) and Markdown. Widths
// count UTF-8 code points, so "512²" and "–" line up.
#include <string>
#include <vector>

namespace vsil::bench {

class TextTable {
 public:
  explicit TextTable(std::vector<std::string> header) : header_(std::move(header)) {}
  void addRow(std::vector<std::string> cells) { rows_.push_back(std::move(cells)); }
  std::string plain() const;
  std::string markdown() const;

 private:
  std::vector<std::string> header_;
  std::vector<std::vector<std::string>> rows_;
};

// Code points in a UTF-8 string (bytes that do not continue a sequence).
std::size_t displayWidth(const std::string& text);

}  // namespace vsil::bench
