#pragma once
// Output files are written whole or not at all: the bytes go to a temporary file in the target's
// directory, which is renamed over the target only once complete.
#include <cstdint>
#include <filesystem>
#include <span>
#include <string_view>

namespace vsil {

// Throws InputError (naming the path) when the directory is missing or not writable.
void writeFileAtomically(const std::filesystem::path& path, std::span<const std::uint8_t> bytes);
void writeFileAtomically(const std::filesystem::path& path, std::string_view text);

}  // namespace vsil
