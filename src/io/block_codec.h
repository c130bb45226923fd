#pragma once
// The compressors of VTK XML binary blocks (vtkZLibDataCompressor, vtkLZ4DataCompressor,
// vtkLZMADataCompressor): each block decompresses to the size the block header gives. Output
// never grows past it: a block that would decompress to more (a bomb, or a header that lies) is
// an error, found after at most one piece of output beyond it (LZ4: decoded into a buffer of
// exactly the expected size, which LZ4_decompress_safe never overruns).
#include <cstdint>
#include <functional>
#include <span>
#include <string>

namespace vsil::io {

enum class BlockCodec { Zlib, Lz4, Lzma };

// "zlib", "lz4", "lzma" (messages: "lz4 block 3 ...").
const char* blockCodecName(BlockCodec codec);

// Throws InputError naming `where` when `compressedBytes` cannot decompress to `expected`
// bytes with this codec (each has a maximum ratio: zlib 1032, LZ4 255; xz has no useful bound).
void checkDecompressible(const std::string& where, const std::string& what, BlockCodec codec,
                         std::uint64_t compressedBytes, std::uint64_t expected);

// Decompresses one complete block into exactly `expected` bytes handed to `write` in order.
// Throws InputError naming `where` and `what` (e.g. "lz4 block 3") if the block is corrupt,
// truncated, or decompresses to any other size.
void decompressBlock(const std::string& where, const std::string& what, BlockCodec codec,
                     std::span<const std::uint8_t> compressed, std::uint64_t expected,
                     const std::function<void(std::span<const std::uint8_t>)>& write);

}  // namespace vsil::io
