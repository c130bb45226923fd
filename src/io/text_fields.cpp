#include "io/text_fields.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <limits>

#include "core/error.h"
#include "core/options.h"

namespace vsil::io {
namespace {

bool isSpace(char c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f';
}

}  // namespace

std::string_view trim(std::string_view text) {
  while (!text.empty() && isSpace(text.front())) text.remove_prefix(1);
  while (!text.empty() && isSpace(text.back())) text.remove_suffix(1);
  return text;
}

std::string toLower(std::string_view text) {
  std::string lower(text);
  for (char& c : lower) {
    if (c >= 'A' && c <= 'Z') c = char(c - 'A' + 'a');
  }
  return lower;
}

std::vector<std::string_view> splitWhitespace(std::string_view text) {
  std::vector<std::string_view> tokens;
  std::size_t i = 0;
  while (i < text.size()) {
    while (i < text.size() && isSpace(text[i])) ++i;
    const std::size_t start = i;
    while (i < text.size() && !isSpace(text[i])) ++i;
    if (i > start) tokens.push_back(text.substr(start, i - start));
  }
  return tokens;
}

std::string dataFilePath(const std::string& header, const std::string& label,
                         const std::string& name) {
  if (name.find('\0') != std::string::npos) {
    throwInputError(header, label + ": a file name cannot hold a NUL byte");
  }
  std::filesystem::path path(name);
  if (path.is_relative()) path = std::filesystem::path(header).parent_path() / path;
  return path.string();
}

std::string quote(std::string_view text) {
  constexpr std::size_t kMaxShown = 40;
  return "'" + printableText(std::string(text.substr(0, kMaxShown))) +
         (text.size() > kMaxShown ? "...'" : "'");
}

namespace {

// from_chars for integers and reals alike; `noun` names what the field should hold.
template <typename Number>
Number parseNumber(const std::string& where, const std::string& field, std::string_view token,
                   const char* noun) {
  Number value{};
  const char* end = token.data() + token.size();
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  const auto [stop, error] = std::from_chars(token.data(), end, value);
  if (error == std::errc::result_out_of_range) {
    throwInputError(where, field + " value " + quote(token) + " is out of range");
  }
  if (token.empty() || error != std::errc() || stop != end) {
    throwInputError(where, field + " value " + quote(token) + " is not " + noun);
  }
  return value;
}

}  // namespace

std::int64_t parseInteger(const std::string& where, const std::string& field,
                          std::string_view token) {
  return parseNumber<std::int64_t>(where, field, token, "an integer");
}

double parseReal(const std::string& where, const std::string& field, std::string_view token) {
  return parseNumber<double>(where, field, token, "a number");
}

glm::ivec3 parseDims(const std::string& where, const std::string& field, std::string_view text) {
  const auto tokens = splitWhitespace(text);
  if (tokens.size() != 3) {
    throwInputError(where, field + " needs 3 values, found " + std::to_string(tokens.size()));
  }
  glm::ivec3 dims;
  for (int axis = 0; axis < 3; ++axis) {
    const std::int64_t value = parseInteger(where, field, tokens[axis]);
    if (value <= 0) {
      throwInputError(where, field + " value " + std::to_string(value) + " is not a positive size");
    }
    if (value > std::numeric_limits<int>::max()) {
      throwInputError(where, field + " value " + std::to_string(value) + " is too large (at most " +
                                 std::to_string(std::numeric_limits<int>::max()) + ")");
    }
    dims[axis] = int(value);
  }
  return dims;
}

void checkSpacing(const std::string& where, const std::string& field, glm::dvec3 spacing) {
  for (int axis = 0; axis < 3; ++axis) {
    if (!std::isfinite(spacing[axis]) || spacing[axis] <= 0.0) {
      throwInputError(where, field + " " + formatNumber(spacing[axis]) + " along " + "xyz"[axis] +
                                 " is not a positive, finite distance");
    }
  }
}

glm::dvec3 parseSpacing(const std::string& where, const std::string& field, std::string_view text) {
  const auto tokens = splitWhitespace(text);
  if (tokens.size() != 3) {
    throwInputError(where, field + " needs 3 values, found " + std::to_string(tokens.size()));
  }
  glm::dvec3 spacing;
  for (int axis = 0; axis < 3; ++axis) spacing[axis] = parseReal(where, field, tokens[axis]);
  checkSpacing(where, field, spacing);
  return spacing;
}

}  // namespace vsil::io
