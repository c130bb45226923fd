#pragma once
// zlib inflation of a stream of known inflated size, streamed in pieces. The output never
// grows: a stream that would decompress to more than expected (a "zip bomb", or a wrong header)
// is an error, found after at most one extra piece of output.
#include <cstdint>
#include <functional>
#include <span>
#include <string>

namespace vsil::io {

enum class DeflateWrapper { Zlib, Gzip };

// Inflates one complete stream (with Gzip, one or more members, as gzip reads them) into
// exactly `expected` bytes: `read` hands out the compressed
// bytes in pieces (an empty piece when there are no more), `write` receives the inflated bytes
// in order, in pieces of at most 1 MiB + 1. Throws InputError naming `where` (and `what`, e.g.
// "zlib block 3") if the stream is corrupt, truncated, inflates to any other size, or is
// followed by anything but padding (isStreamPadding).
void inflateStream(const std::string& where, const std::string& what, DeflateWrapper wrapper,
                   std::uint64_t expected,
                   const std::function<std::span<const std::uint8_t>()>& read,
                   const std::function<void(std::span<const std::uint8_t>)>& write);

// True where bytes after a compressed stream are a writer's padding (NUL bytes, whitespace), as
// gzip takes them; anything else there means the header's sizes are not the file's.
bool isStreamPadding(std::span<const std::uint8_t> bytes);

// Deflate packs at most 1032:1; fewer compressed bytes than expected/1032 cannot hold the data.
// Throws InputError before anything is allocated for them.
void checkInflatable(const std::string& where, const std::string& what,
                     std::uint64_t compressedBytes, std::uint64_t expected);

}  // namespace vsil::io
