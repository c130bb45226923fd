#pragma once
// zlib inflation into a buffer of known size. The output never grows: a stream that would
// decompress to more than expected (a "zip bomb", or a wrong header) is an error, found after
// at most one extra byte of output.
#include <cstdint>
#include <span>
#include <string>

namespace vsil::io {

enum class DeflateWrapper { Zlib, Gzip };

// Inflates one complete stream from `compressed` into exactly `out.size()` bytes. Throws
// InputError naming `where` (and `what`, e.g. "zlib block 3") if the stream is corrupt,
// truncated, or inflates to any other size. Bytes after the end of the stream are ignored.
void inflateExactly(const std::string& where, const std::string& what,
                    std::span<const std::uint8_t> compressed, std::span<std::uint8_t> out,
                    DeflateWrapper wrapper);

// Deflate packs at most 1032:1; fewer compressed bytes than expected/1032 cannot hold the data.
// Throws InputError before anything is allocated for them.
void checkInflatable(const std::string& where, const std::string& what,
                     std::uint64_t compressedBytes, std::uint64_t expected);

}  // namespace vsil::io
