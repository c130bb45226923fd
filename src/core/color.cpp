#include "core/color.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdio>
#include <utility>

#include "core/error.h"

namespace vsil {
namespace {

constexpr std::array<std::pair<const char*, Rgba>, 14> kNamedColors{{
    {"black", {0, 0, 0, 255}},
    {"white", {255, 255, 255, 255}},
    {"red", {255, 0, 0, 255}},
    {"green", {0, 128, 0, 255}},
    {"blue", {0, 0, 255, 255}},
    {"yellow", {255, 255, 0, 255}},
    {"cyan", {0, 255, 255, 255}},
    {"magenta", {255, 0, 255, 255}},
    {"grey", {128, 128, 128, 255}},
    {"gray", {128, 128, 128, 255}},
    {"orange", {255, 165, 0, 255}},
    {"navy", {0, 0, 128, 255}},
    {"ivory", {255, 255, 240, 255}},
    {"transparent", {0, 0, 0, 0}},
}};

int hexDigit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  c = char(std::tolower(static_cast<unsigned char>(c)));
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  return -1;
}

[[noreturn]] void throwBadColor(const std::string& text, const std::string& flagName) {
  throwInputError(flagName, "'" + text +
                                "' is not a colour (use a name such as black, white, red, or "
                                "#rgb, #rrggbb, #rrggbbaa)");
}

}  // namespace

std::string Rgba::hex() const {
  char text[16];
  std::snprintf(text, sizeof text, "#%02x%02x%02x%02x", r & 255, g & 255, b & 255, a & 255);
  return text;
}

Rgba parseColor(const std::string& text, const std::string& flagName) {
  std::string lower = text;
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  for (const auto& [name, color] : kNamedColors) {
    if (lower == name) return color;
  }
  const auto bad = [&]() { throwBadColor(text, flagName); };
  if (lower.empty() || lower[0] != '#') bad();
  const std::string hex = lower.substr(1);
  for (char c : hex) {
    if (hexDigit(c) < 0) bad();
  }
  if (hex.size() == 3) {
    return {hexDigit(hex[0]) * 17, hexDigit(hex[1]) * 17, hexDigit(hex[2]) * 17, 255};
  }
  const auto byte = [&](std::size_t i) { return hexDigit(hex[i]) * 16 + hexDigit(hex[i + 1]); };
  if (hex.size() == 6) return {byte(0), byte(2), byte(4), 255};
  if (hex.size() == 8) return {byte(0), byte(2), byte(4), byte(6)};
  throwBadColor(text, flagName);
}

Rgba parseOpaqueColor(const std::string& text, const std::string& flagName,
                      const std::string& why) {
  const Rgba color = parseColor(text, flagName);
  if (color.a != 255) {
    throwInputError(flagName, "'" + text + "' has an alpha below ff, and " + why +
                                  ": give #rgb, #rrggbb or a name");
  }
  return color;
}

}  // namespace vsil
