#pragma once
// Base64 (RFC 4648) as VTK writes it: whitespace is ignored, and '=' padding may end a quantum
// in the middle of the text (VTK encodes a data header and the data separately, so the text
// may read "AAAA==BBBB..."). Each quantum decodes independently.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace vsil::io {

// Throws InputError naming `where` for a character outside the alphabet or a dangling quantum.
std::vector<std::uint8_t> decodeBase64(const std::string& where, std::string_view text);

}  // namespace vsil::io
