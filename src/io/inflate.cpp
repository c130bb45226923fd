#include "io/inflate.h"

#include <algorithm>
#include <limits>
#include <vector>

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

  // Ready for the next gzip member: one gzip file may hold several, read one after another.
  void nextMember() {
    if (inflateReset(&stream_) != Z_OK) fail("could not restart zlib");
  }

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

void inflateStream(const std::string& where, const std::string& what, DeflateWrapper wrapper,
                   std::uint64_t expected,
                   const std::function<std::span<const std::uint8_t>()>& read,
                   const std::function<void(std::span<const std::uint8_t>)>& write) {
  constexpr std::size_t kPiece = std::size_t(1) << 20;
  InflateStream stream(where, what, wrapper);
  std::vector<std::uint8_t> buffer(std::size_t(std::min<std::uint64_t>(expected, kPiece)) + 1);
  std::span<const std::uint8_t> in;
  std::vector<std::uint8_t> joined;  // a piece's last byte and the next piece, where needed
  std::uint64_t produced = 0;
  bool ended = false;
  while (!ended) {
    if (in.empty()) in = read();  // empty again: no more input, and step() says "truncated"
    // Room for what is still expected plus one byte: a byte beyond it is a bomb (or a header
    // that lies), found without inflating further.
    std::span<std::uint8_t> out(
        buffer.data(),
        std::size_t(std::min<std::uint64_t>(buffer.size() - 1, expected - produced)) + 1);
    const std::size_t before = in.size() + out.size();
    ended = stream.step(in, out);
    const auto made = std::size_t(out.data() - buffer.data());
    if (produced + made > expected) {
      stream.fail("inflates to more than the " + std::to_string(expected) + " bytes expected");
    }
    if (made) write(std::span<const std::uint8_t>(buffer.data(), made));
    produced += made;
    if (!ended && in.size() + out.size() == before && !in.empty()) stream.fail("makes no progress");
    if (ended && wrapper == DeflateWrapper::Gzip) {
      // Another member may follow, after NUL padding, as gzip reads on through both.
      for (;;) {
        while (!in.empty() && in.front() == 0) in = in.subspan(1);
        if (!in.empty() || (in = read()).empty()) break;
      }
      if (in.size() == 1) {  // the magic may straddle two pieces
        joined.assign(in.begin(), in.end());
        const auto more = read();
        joined.insert(joined.end(), more.begin(), more.end());
        in = joined;
      }
      if (in.size() >= 2 && in[0] == 0x1f && in[1] == 0x8b) {  // the next member's magic
        stream.nextMember();
        ended = false;
      }
    }
  }
  if (produced != expected) {
    // Bytes that neither pad nor start another member (a blank between two gzip members, which
    // gzip refuses too) end the stream early: say so, not only that samples are missing.
    const bool otherBytes = !in.empty() && !isStreamPadding(in);
    stream.fail("inflates to " + std::to_string(produced) + " bytes, " + std::to_string(expected) +
                " expected" +
                (otherBytes ? wrapper == DeflateWrapper::Gzip
                                  ? " (bytes follow its end that are not another gzip member)"
                                  : " (bytes follow its end)"
                            : ""));
  }
  do {
    if (!isStreamPadding(in)) stream.fail("is followed by bytes that are not part of it");
    in = read();
  } while (!in.empty());
}

bool isStreamPadding(std::span<const std::uint8_t> bytes) {
  return std::all_of(bytes.begin(), bytes.end(), [](std::uint8_t b) {
    return b == 0 || b == ' ' || b == '\t' || b == '\n' || b == '\r';
  });
}

}  // namespace vsil::io
