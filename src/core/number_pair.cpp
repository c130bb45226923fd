#include "core/number_pair.h"

#include <cmath>
#include <cstdlib>

#include "core/error.h"

namespace vsil {

namespace {

bool parseDouble(const std::string& text, double& value) {
  if (text.empty()) return false;
  char* end = nullptr;
  value = std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size() && std::isfinite(value);
}

}  // namespace

glm::dvec2 parseNumberPair(const std::string& flag, const std::string& text) {
  const auto comma = text.find(',');
  glm::dvec2 pair;
  if (comma == std::string::npos || !parseDouble(text.substr(0, comma), pair.x) ||
      !parseDouble(text.substr(comma + 1), pair.y)) {
    throw InputError(flag + ": '" + text + "' is not a pair of numbers A,B");
  }
  return pair;
}

}  // namespace vsil
