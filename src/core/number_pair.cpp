#include "core/number_pair.h"

#include <charconv>
#include <cmath>
#include <string_view>

#include "core/error.h"

namespace vsil {

namespace {

// A decimal number written whole, '+' allowed: from_chars, not strtod, which also took
// hexadecimal (0x1e read as 30), leading blanks and the locale's decimal separator.
bool parseDouble(const std::string& text, double& value) {
  std::string_view number = text;
  if (number.starts_with('+')) number.remove_prefix(1);
  if (number.empty() || number.starts_with('+') || (text.starts_with('+') && number[0] == '-')) {
    return false;
  }
  const auto [ptr, ec] = std::from_chars(number.data(), number.data() + number.size(), value);
  return ec == std::errc() && ptr == number.data() + number.size() && std::isfinite(value);
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
