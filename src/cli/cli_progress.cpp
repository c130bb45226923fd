#include "cli/cli_progress.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <iostream>

namespace vsil::cli {
namespace {

constexpr auto kQuietFor = std::chrono::seconds(1);

}  // namespace

ProgressLine::ProgressLine(std::string what)
    : what_(std::move(what)), start_(std::chrono::steady_clock::now()), terminal_(isatty(2)) {}

std::function<void(std::uint64_t, std::uint64_t)> ProgressLine::callback() {
  return [this](std::uint64_t done, std::uint64_t total) {
    const int percent = total ? int(100 * done / total) : 0;
    if (percent == shownPercent_) return;
    if (std::chrono::steady_clock::now() - start_ < kQuietFor) return;
    shownPercent_ = percent;
    show(what_ + " " + std::to_string(percent) + "%");
  };
}

void ProgressLine::step(const std::string& what) {
  if (std::chrono::steady_clock::now() - start_ < kQuietFor) return;
  what_ = what;
  shownPercent_ = -1;
  show(what);
}

void ProgressLine::show(const std::string& text) {
  if (!terminal_) {
    if (announced_ != what_) std::cerr << "vsil: " << what_ << " ...\n" << std::flush;
    announced_ = what_;
    return;
  }
  const std::string line = "vsil: " + text;
  std::cerr << "\r" << line;
  if (line.size() < shownWidth_) std::cerr << std::string(shownWidth_ - line.size(), ' ');
  std::cerr << std::flush;
  shownWidth_ = line.size();
}

void ProgressLine::finish() {
  if (!terminal_ || shownWidth_ == 0) return;
  std::cerr << "\r" << std::string(shownWidth_, ' ') << "\r" << std::flush;
  shownWidth_ = 0;
}

std::string progressText(int done, int total, double seconds, ProgressUnit unit,
                         const std::string& note) {
  constexpr int kBar = 20;
  const int filled = total > 0 ? int(std::lround(double(kBar) * done / total)) : kBar;
  std::string text = std::string(unit.noun) + " " + std::to_string(done) + "/" +
                     std::to_string(total) + " [" + std::string(filled, '#') +
                     std::string(kBar - filled, ' ') + "]";
  if (!note.empty()) text += " " + note;
  if (seconds > 0 && done > 0) {
    const double rate = done / seconds;
    char tail[64];
    std::snprintf(tail, sizeof tail, " %.1f %s, %.0f s left", rate, unit.rate,
                  (total - done) / rate);
    text += tail;
  }
  return text;
}

}  // namespace vsil::cli
