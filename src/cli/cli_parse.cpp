#include "cli/cli_parse.h"

#include <cmath>
#include <cstdlib>
#include <limits>

#include "core/error.h"

namespace vsil::cli {
namespace {

bool parseInt(const std::string& text, int& value) {
  if (text.empty() || text.size() > 9) return false;
  for (char c : text) {
    if (c < '0' || c > '9') return false;
  }
  value = std::atoi(text.c_str());
  return true;
}

bool parseDouble(const std::string& text, double& value) {
  if (text.empty()) return false;
  char* end = nullptr;
  value = std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size() && std::isfinite(value);
}

}  // namespace

glm::ivec2 parseSize(const std::string& flag, const std::string& text) {
  const auto x = text.find_first_of("xX");
  glm::ivec2 size;
  if (x == std::string::npos || !parseInt(text.substr(0, x), size.x) ||
      !parseInt(text.substr(x + 1), size.y) || size.x < 1 || size.y < 1) {
    throw InputError(flag + ": '" + text + "' is not a size WxH with positive integers");
  }
  return size;
}

glm::dvec2 parsePair(const std::string& flag, const std::string& text) {
  const auto comma = text.find(',');
  glm::dvec2 pair;
  if (comma == std::string::npos || !parseDouble(text.substr(0, comma), pair.x) ||
      !parseDouble(text.substr(comma + 1), pair.y)) {
    throw InputError(flag + ": '" + text + "' is not a pair of numbers A,B");
  }
  return pair;
}

}  // namespace vsil::cli
