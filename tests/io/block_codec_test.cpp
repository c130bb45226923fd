// VTI's zlib blocks (io/block_codec.h): blocks up to 1 MiB inflate whole through libdeflate,
// larger ones stream through zlib; both give the same bytes, and a block either way refuses
// alike with zlib's message.
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "core/error.h"
#include "io/block_codec.h"
#include "io_test_files.h"

namespace vsil::io {
namespace {

using test::Bytes;

constexpr std::size_t kMiB = std::size_t(1) << 20;

// Compressible but not trivially: runs of random bytes.
Bytes noisyRuns(std::size_t size, unsigned seed) {
  std::mt19937 random(seed);
  Bytes bytes(size);
  for (std::size_t i = 0; i < size;) {
    const std::uint8_t value = std::uint8_t(random());
    for (std::size_t run = 1 + random() % 9; run > 0 && i < size; --run) bytes[i++] = value;
  }
  return bytes;
}

Bytes inflated(std::span<const std::uint8_t> compressed, std::uint64_t expected) {
  Bytes out;
  decompressBlock("image.vti", "zlib block 0", BlockCodec::Zlib, compressed, expected,
                  [&](std::span<const std::uint8_t> piece) {
                    out.insert(out.end(), piece.begin(), piece.end());
                  });
  return out;
}

std::string inflateError(std::span<const std::uint8_t> compressed, std::uint64_t expected) {
  try {
    inflated(compressed, expected);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(ZlibBlock, InflatesToTheSameBytesWholeOrStreamed) {
  for (const std::size_t size : {std::size_t(0), std::size_t(1), std::size_t(32768), kMiB - 1, kMiB,
                                 kMiB + 1, 3 * kMiB + 5}) {
    const Bytes data = noisyRuns(size, unsigned(size));
    Bytes compressed = test::deflateBytes(data, false);
    EXPECT_EQ(inflated(compressed, size), data) << size;
    // A writer's padding after the stream's end is read past either way; other bytes there
    // are refused either way.
    Bytes padded = compressed;
    padded.insert(padded.end(), {0, 0, '\n', ' '});
    EXPECT_EQ(inflated(padded, size), data) << size << " with padding";
    compressed.insert(compressed.end(), {0, 1, 2, 3});
    EXPECT_EQ(inflateError(compressed, size),
              "image.vti: zlib block 0 is followed by bytes that are not part of it")
        << size;
  }
}

TEST(ZlibBlock, RefusesAlikeOnEitherSideOfTheWholeBlockSize) {
  for (const std::size_t size : {std::size_t(4096), kMiB, kMiB + 1, 2 * kMiB}) {
    SCOPED_TRACE(size);
    const Bytes data = noisyRuns(size, 7);
    const Bytes compressed = test::deflateBytes(data, false);
    EXPECT_EQ(inflateError(compressed, size - 1),
              "image.vti: zlib block 0 inflates to more than the " + std::to_string(size - 1) +
                  " bytes expected");
    EXPECT_EQ(inflateError(compressed, size + 1), "image.vti: zlib block 0 inflates to " +
                                                      std::to_string(size) + " bytes, " +
                                                      std::to_string(size + 1) + " expected");
    const Bytes cut(compressed.begin(), compressed.begin() + std::ptrdiff_t(compressed.size() / 2));
    EXPECT_EQ(inflateError(cut, size), "image.vti: zlib block 0 is truncated");
    Bytes corrupt = compressed;
    corrupt[corrupt.size() - 1] ^= 0xff;  // the Adler-32 check value
    EXPECT_EQ(inflateError(corrupt, size),
              "image.vti: zlib block 0 is corrupt (zlib: incorrect data check)");
    EXPECT_EQ(inflateError(compressed, size), "no error");
  }
}

}  // namespace
}  // namespace vsil::io
