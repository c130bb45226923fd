#include "io/base64.h"

#include "core/error.h"

namespace vsil::io {
namespace {

// 0..63 for alphabet characters, -1 for '=', -2 for whitespace, -3 otherwise.
int classify(char c) {
  if (c >= 'A' && c <= 'Z') return c - 'A';
  if (c >= 'a' && c <= 'z') return c - 'a' + 26;
  if (c >= '0' && c <= '9') return c - '0' + 52;
  if (c == '+') return 62;
  if (c == '/') return 63;
  if (c == '=') return -1;
  if (c == ' ' || c == '\n' || c == '\r' || c == '\t') return -2;
  return -3;
}

}  // namespace

std::vector<std::uint8_t> decodeBase64(const std::string& where, std::string_view text) {
  std::vector<std::uint8_t> bytes;
  bytes.reserve(text.size() / 4 * 3 + 3);
  int quantum[4];
  int filled = 0;  // characters of the current quantum, '=' included
  int padding = 0;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const int value = classify(text[i]);
    if (value == -2) continue;
    if (value == -3) {
      throwInputError(where, "base64 text has an invalid character at offset " + std::to_string(i));
    }
    if (value == -1) {
      if (filled < 2)
        throwInputError(where, "base64 padding at offset " + std::to_string(i) + " is misplaced");
      ++padding;
    } else if (padding > 0) {
      throwInputError(
          where, "base64 data follows padding inside a quantum at offset " + std::to_string(i));
    }
    quantum[filled++] = value < 0 ? 0 : value;
    if (filled == 4) {
      const std::uint32_t bits = std::uint32_t(quantum[0]) << 18 | std::uint32_t(quantum[1]) << 12 |
                                 std::uint32_t(quantum[2]) << 6 | std::uint32_t(quantum[3]);
      bytes.push_back(std::uint8_t(bits >> 16));
      if (padding < 2) bytes.push_back(std::uint8_t(bits >> 8));
      if (padding < 1) bytes.push_back(std::uint8_t(bits));
      filled = 0;
      padding = 0;
    }
  }
  if (filled != 0) {
    throwInputError(where, "base64 text ends inside a quantum (" + std::to_string(filled) +
                               " of 4 characters)");
  }
  return bytes;
}

}  // namespace vsil::io
