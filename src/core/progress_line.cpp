#include "core/progress_line.h"

namespace vsil {

void ProgressLine::update(const std::string& text) {
  if (terminal_) show(text);
}

void ProgressLine::milestone(const std::string& text) {
  if (terminal_) {
    show(text);
  } else {
    out_ << text << "\n" << std::flush;
  }
}

void ProgressLine::show(const std::string& text) {
  // Pad with spaces over the rest of a longer previous line.
  std::string line = "\r" + text;
  if (text.size() < shownWidth_) line += std::string(shownWidth_ - text.size(), ' ');
  shownWidth_ = text.size();
  out_ << line << std::flush;
}

void ProgressLine::finish() {
  if (!terminal_ || shownWidth_ == 0) return;
  out_ << "\r" << std::string(shownWidth_, ' ') << "\r" << std::flush;
  shownWidth_ = 0;
}

}  // namespace vsil
