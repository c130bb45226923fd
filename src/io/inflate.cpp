#include "io/inflate.h"

#include <algorithm>
#include <limits>

#include <zlib.h>

#include "core/error.h"

namespace vsil::io {
namespace {

// zlib counts in uInt (32 bits); larger buffers are fed in pieces of this size.
constexpr std::size_t kMaxChunk = std::size_t(1) << 30;

class InflateStream {
 public:
  InflateStream(const std::string& where, const std::string& what, DeflateWrapper wrapper)
      : where_(where), what_(what) {
    // windowBits 15 = zlib header; +16 = gzip header only.
    const int windowBits = wrapper == DeflateWrapper::Gzip ? 15 + 16 : 15;
    if (inflateInit2(&stream_, windowBits) != Z_OK) fail("could not start zlib");
  }
  ~InflateStream() { inflateEnd(&stream_); }
  InflateStream(const InflateStream&) = delete;
  InflateStream& operator=(const InflateStream&) = delete;

  [[noreturn]] void fail(const std::string& problem) const {
    throwInputError(where_, what_ + " " + problem);
  }

  // Inflates into `out`, feeding from `in`, until the stream ends, `out` is full, or the input
  // runs out. Returns true when the stream has ended. Advances both spans.
  bool step(std::span<const std::uint8_t>& in, std::span<std::uint8_t>& out) {
    stream_.next_in = const_cast<Bytef*>(in.data());
    stream_.avail_in = uInt(std::min(in.size(), kMaxChunk));
    stream_.next_out = out.data();
    stream_.avail_out = uInt(std::min(out.size(), kMaxChunk));
    const uInt inBefore = stream_.avail_in, outBefore = stream_.avail_out;
    const int result = inflate(&stream_, Z_NO_FLUSH);
    in = in.subspan(inBefore - stream_.avail_in);
    out = out.subspan(outBefore - stream_.avail_out);
    if (result == Z_STREAM_END) return true;
    if (result == Z_OK || result == Z_BUF_ERROR) {
      if (result == Z_BUF_ERROR && in.empty()) fail("is truncated");
      return false;
    }
    if (result == Z_NEED_DICT) fail("needs a preset dictionary");
    fail(std::string("is corrupt (zlib: ") + (stream_.msg ? stream_.msg : "error") + ")");
  }

  std::uint64_t totalOut() const { return stream_.total_out; }

 private:
  z_stream stream_{};
  std::string where_, what_;
};

}  // namespace

void checkInflatable(const std::string& where, const std::string& what,
                     std::uint64_t compressedBytes, std::uint64_t expected) {
  constexpr std::uint64_t kMaxDeflateRatio = 1032;
  if (compressedBytes < expected / kMaxDeflateRatio) {
    throwInputError(where, what + " of " + std::to_string(compressedBytes) +
                               " bytes cannot inflate to the " + std::to_string(expected) +
                               " bytes expected");
  }
}

void inflateExactly(const std::string& where, const std::string& what,
                    std::span<const std::uint8_t> compressed, std::span<std::uint8_t> out,
                    DeflateWrapper wrapper) {
  InflateStream stream(where, what, wrapper);
  const std::size_t expected = out.size();
  std::span<std::uint8_t> rest = out;
  bool ended = false;
  while (!ended) {
    if (rest.empty()) {
      // Full: the stream must end now, without a single further byte.
      std::uint8_t extra = 0;
      std::span<std::uint8_t> probe(&extra, 1);
      const std::size_t inputBefore = compressed.size();
      ended = stream.step(compressed, probe);
      if (probe.empty()) {
        stream.fail("inflates to more than the " + std::to_string(expected) + " bytes expected");
      }
      if (!ended && compressed.empty()) stream.fail("is truncated");
      if (!ended && compressed.size() == inputBefore) stream.fail("makes no progress");
      continue;
    }
    const std::size_t before = rest.size() + compressed.size();
    ended = stream.step(compressed, rest);
    if (!ended && compressed.empty() && !rest.empty()) stream.fail("is truncated");
    if (!ended && rest.size() + compressed.size() == before) stream.fail("makes no progress");
  }
  if (!rest.empty()) {
    stream.fail("inflates to " + std::to_string(expected - rest.size()) + " bytes, " +
                std::to_string(expected) + " expected");
  }
}

}  // namespace vsil::io
