#pragma once
// Reading files with every failure turned into an InputError that names the path: missing,
// a directory, empty, unreadable, shorter than needed, or larger than a caller's bound.
#include <cstdint>
#include <string>
#include <vector>

namespace vsil::io {

// The size of a regular, non-empty file. Throws for a missing path, a directory or other
// non-regular file, an empty file, or one that cannot be opened for reading.
std::uint64_t regularFileSize(const std::string& path);

// Exactly `count` bytes starting at `offset` (the caller has checked the file is long enough;
// a short read still throws).
std::vector<std::uint8_t> readFileBytes(const std::string& path, std::uint64_t offset,
                                        std::uint64_t count);

// The whole file as bytes in a string, refusing files larger than `maxBytes` before reading.
std::string readWholeFile(const std::string& path, std::uint64_t maxBytes);

}  // namespace vsil::io
