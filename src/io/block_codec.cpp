#include "io/block_codec.h"

#include <algorithm>
#include <limits>
#include <memory>
#include <vector>

#include <libdeflate.h>
#include <lz4.h>
#include <lzma.h>

#include "core/error.h"
#include "io/inflate.h"

namespace vsil::io {
namespace {

// An xz block of VTK's holds one compressed buffer; its decoder needs little memory, and a
// stream asking for more than this (a crafted dictionary size) is refused by liblzma.
constexpr std::uint64_t kLzmaMemoryLimit = std::uint64_t(256) << 20;

class XzDecoder {
 public:
  XzDecoder(const std::string& where, const std::string& what) : where_(where), what_(what) {
    if (lzma_stream_decoder(&stream_, kLzmaMemoryLimit, 0) != LZMA_OK) fail("could not start xz");
  }
  ~XzDecoder() { lzma_end(&stream_); }
  XzDecoder(const XzDecoder&) = delete;
  XzDecoder& operator=(const XzDecoder&) = delete;

  [[noreturn]] void fail(const std::string& problem) const {
    throwInputError(where_, what_ + " " + problem);
  }

  // Decodes all of `in`, handing at most `expected` + 1 bytes of output to `write` in pieces;
  // returns how many bytes it produced (more than `expected` means it stopped there).
  std::uint64_t run(std::span<const std::uint8_t> in, std::uint64_t expected,
                    const std::function<void(std::span<const std::uint8_t>)>& write) {
    constexpr std::size_t kPiece = std::size_t(1) << 20;
    std::vector<std::uint8_t> buffer(std::size_t(std::min<std::uint64_t>(expected, kPiece)) + 1);
    stream_.next_in = in.data();
    stream_.avail_in = in.size();
    std::uint64_t produced = 0;
    while (true) {
      const std::size_t room =
          std::size_t(std::min<std::uint64_t>(buffer.size() - 1, expected - produced)) + 1;
      stream_.next_out = buffer.data();
      stream_.avail_out = room;
      const lzma_ret result = lzma_code(&stream_, LZMA_FINISH);
      const std::size_t made = room - stream_.avail_out;
      if (produced + made > expected) return produced + made;
      if (made) write(std::span<const std::uint8_t>(buffer.data(), made));
      produced += made;
      if (result == LZMA_STREAM_END) return produced;
      // No progress twice in a row is LZMA_BUF_ERROR: all input was given, so it is truncated.
      if (result == LZMA_OK) continue;
      if (result == LZMA_BUF_ERROR) fail("is truncated");
      if (result == LZMA_MEMLIMIT_ERROR) fail("needs more memory than an xz block may use");
      if (result == LZMA_FORMAT_ERROR) fail("is not an xz stream");
      fail("is corrupt (xz error " + std::to_string(int(result)) + ")");
    }
  }

 private:
  lzma_stream stream_ = LZMA_STREAM_INIT;
  std::string where_, what_;
};

// libdeflate inflates a zlib block about 2.5 times as fast as zlib (bonsai.vti's 512 blocks of
// 32 KiB: 37 -> 15 ms), but only whole, into memory for all of it: blocks up to the size of
// zlib's own output piece (inflate.h) go that way. Any outcome but exactly `expected` bytes
// falls back to zlib, whose decode then gives the error its message.
constexpr std::uint64_t kWholeBlockBytes = std::uint64_t(1) << 20;

bool inflateWhole(std::span<const std::uint8_t> compressed, std::uint64_t expected,
                  const std::function<void(std::span<const std::uint8_t>)>& write) {
  if (expected > kWholeBlockBytes) return false;
  const std::unique_ptr<libdeflate_decompressor, decltype(&libdeflate_free_decompressor)>
      decompressor(libdeflate_alloc_decompressor(), &libdeflate_free_decompressor);
  if (!decompressor) return false;
  const auto out = std::make_unique_for_overwrite<std::uint8_t[]>(std::size_t(expected));
  std::size_t read = 0, made = 0;
  // Anything else than what inflateStream accepts goes there, for its error.
  if (libdeflate_zlib_decompress_ex(decompressor.get(), compressed.data(), compressed.size(),
                                    out.get(), std::size_t(expected), &read,
                                    &made) != LIBDEFLATE_SUCCESS ||
      made != expected || !isStreamPadding(compressed.subspan(read))) {
    return false;
  }
  if (made) write(std::span<const std::uint8_t>(out.get(), made));
  return true;
}

}  // namespace

const char* blockCodecName(BlockCodec codec) {
  switch (codec) {
    case BlockCodec::Zlib:
      return "zlib";
    case BlockCodec::Lz4:
      return "lz4";
    case BlockCodec::Lzma:
      return "lzma";
  }
  return "";
}

void checkDecompressible(const std::string& where, const std::string& what, BlockCodec codec,
                         std::uint64_t compressedBytes, std::uint64_t expected) {
  if (codec == BlockCodec::Zlib) {
    checkInflatable(where, what, compressedBytes, expected);
  } else if (codec == BlockCodec::Lz4) {
    constexpr std::uint64_t kMaxLz4Ratio = 255;  // one literal-length byte per 255 output bytes
    if (compressedBytes < expected / kMaxLz4Ratio) {
      throwInputError(where, what + " of " + std::to_string(compressedBytes) +
                                 " bytes cannot decompress to the " + std::to_string(expected) +
                                 " bytes expected");
    }
  }
}

void decompressBlock(const std::string& where, const std::string& what, BlockCodec codec,
                     std::span<const std::uint8_t> compressed, std::uint64_t expected,
                     const std::function<void(std::span<const std::uint8_t>)>& write) {
  if (codec == BlockCodec::Zlib) {
    if (inflateWhole(compressed, expected, write)) return;
    bool given = false;
    inflateStream(
        where, what, DeflateWrapper::Zlib, expected,
        [&] {
          const auto piece = given ? std::span<const std::uint8_t>() : compressed;
          given = true;
          return piece;
        },
        write);
    return;
  }
  if (codec == BlockCodec::Lz4) {
    constexpr auto kMaxInt = std::uint64_t(std::numeric_limits<int>::max());
    if (compressed.size() > kMaxInt || expected > kMaxInt) {
      throwInputError(where, what + " is larger than LZ4 blocks can be (2 GiB)");
    }
    std::vector<std::uint8_t> out(static_cast<std::size_t>(expected));
    const int made = LZ4_decompress_safe(reinterpret_cast<const char*>(compressed.data()),
                                         reinterpret_cast<char*>(out.data()),
                                         int(compressed.size()), int(expected));
    if (made < 0) {
      throwInputError(where, what + " is corrupt or decompresses to more than the " +
                                 std::to_string(expected) + " bytes expected");
    }
    if (std::uint64_t(made) != expected) {
      throwInputError(where, what + " decompresses to " + std::to_string(made) + " bytes, " +
                                 std::to_string(expected) + " expected");
    }
    write(out);
    return;
  }
  XzDecoder decoder(where, what);
  const std::uint64_t produced = decoder.run(compressed, expected, write);
  if (produced > expected) {
    decoder.fail("decompresses to more than the " + std::to_string(expected) + " bytes expected");
  }
  if (produced != expected) {
    decoder.fail("decompresses to " + std::to_string(produced) + " bytes, " +
                 std::to_string(expected) + " expected");
  }
}

}  // namespace vsil::io
