#include "harness/progress.h"

namespace vsil::bench {

void Progress::startCase(const std::string& label) {
  ++current_;
  label_ = label;
  const std::string text =
      "[" + std::to_string(current_) + "/" + std::to_string(total_) + "] " + label_;
  if (terminal_) {
    show(text);
  } else {
    out_ << text << "\n" << std::flush;
  }
}

void Progress::step(const std::string& what) {
  if (!terminal_) return;
  show("[" + std::to_string(current_) + "/" + std::to_string(total_) + "] " + label_ + " " + what);
}

void Progress::show(const std::string& text) {
  // Pad with spaces over the rest of a longer previous line.
  std::string line = "\r" + text;
  if (text.size() < shownWidth_) line += std::string(shownWidth_ - text.size(), ' ');
  shownWidth_ = text.size();
  out_ << line << std::flush;
}

void Progress::finish() {
  if (!terminal_ || shownWidth_ == 0) return;
  out_ << "\r" << std::string(shownWidth_, ' ') << "\r" << std::flush;
  shownWidth_ = 0;
}

}  // namespace vsil::bench
