#include "harness/progress.h"

namespace vsil::bench {

std::string Progress::counter() const {
  return "[" + std::to_string(current_) + "/" + std::to_string(total_) + "] ";
}

void Progress::startCase(const std::string& label) {
  ++current_;
  label_ = label;
  line_.milestone(counter() + label_);
}

void Progress::step(const std::string& what) {
  line_.update(counter() + label_ + " " + what);
}

}  // namespace vsil::bench
