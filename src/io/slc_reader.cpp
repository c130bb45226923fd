// VolVis SLC (.slc), the format of the classic NegHip and iron protein files, as VTK's
// vtkSLCReader reads it: an ASCII header (magic 11111; x y z sizes and bits per voxel, 8 only;
// x y z spacing; units, data origin, data modification, compression 0 = none or 1 = RLE), an
// icon ("W H X" and W·H bytes each of red, green and blue), then the slices along z, each of
// x·y samples (x fastest): uncompressed, the x·y bytes alone; run-length, "N X" and N bytes of
// 8-bit RLE: a control byte whose low 7 bits give a count n (0 ends the slice); with the high
// bit set n literal bytes follow, else the next byte is repeated n times. The numbers are read
// as VTK's fscanf reads them: "%d X" takes "22X" too, and a header may be of any length.
#include <algorithm>
#include <cctype>
#include <limits>
#include <span>

#include "core/error.h"
#include "io/file_access.h"
#include "io/readers.h"
#include "io/text_fields.h"

namespace vsil::io {
namespace {

constexpr int kSlcMagic = 11111;
constexpr int kMaxIcon = 1024;  // icon pixels per side (VolVis writes 100 x 100)
// The first part of the file its header is read from, to bound the rest before reading it all.
constexpr std::uint64_t kHeaderPart = 64 * 1024;

// The file in memory (or the first part of it, `partOfFile`), read token by token where it is
// text.
class SlcCursor {
 public:
  SlcCursor(const std::string& path, std::string_view bytes, bool partOfFile, std::size_t at = 0)
      : path_(path), bytes_(bytes), partOfFile_(partOfFile), at_(at) {}
  std::size_t offset() const { return at_; }

  std::string_view token(const std::string& what) {
    skipSpace();
    const std::size_t start = at_;
    while (at_ < bytes_.size() && !std::isspace(static_cast<unsigned char>(bytes_[at_]))) ++at_;
    if (start == at_) endsBefore(what);
    if (at_ == bytes_.size() && partOfFile_) beyondPart();
    return bytes_.substr(start, at_ - start);
  }
  std::int64_t integer(const std::string& what) { return parseInteger(path_, what, token(what)); }
  double real(const std::string& what) { return parseReal(path_, what, token(what)); }
  // A count that an 'X' may follow without a blank ("22X", as fscanf's "%d X" reads it): its
  // digits alone.
  std::int64_t count(const std::string& what) {
    skipSpace();
    const std::size_t start = at_;
    if (at_ < bytes_.size() && (bytes_[at_] == '+' || bytes_[at_] == '-')) ++at_;
    while (at_ < bytes_.size() && std::isdigit(static_cast<unsigned char>(bytes_[at_]))) ++at_;
    if (at_ == bytes_.size() && start == at_) endsBefore(what);
    if (start == at_ || !std::isdigit(static_cast<unsigned char>(bytes_[at_ - 1]))) {
      throwInputError(path_, what + " is not a number (\"N X\" expected)");
    }
    return parseInteger(path_, what, bytes_.substr(start, at_ - start));
  }
  // The 'X' that ends a size line; the binary bytes follow it directly.
  void marker(const std::string& what) {
    skipSpace();
    if (at_ == bytes_.size() || bytes_[at_] != 'X') {
      throwInputError(path_, what + " is not followed by 'X'");
    }
    ++at_;
  }
  std::string_view bytes(std::uint64_t count, const std::string& what) {
    if (count > bytes_.size() - at_) {
      throwInputError(path_, what + " needs " + std::to_string(count) + " bytes, the file holds " +
                                 std::to_string(bytes_.size() - at_) + " more");
    }
    const std::string_view part = bytes_.substr(at_, std::size_t(count));
    at_ += std::size_t(count);
    return part;
  }
  // Whether only padding (whitespace, NUL bytes) is left.
  bool atEnd() {
    while (at_ < bytes_.size() &&
           (std::isspace(static_cast<unsigned char>(bytes_[at_])) || bytes_[at_] == '\0')) {
      ++at_;
    }
    return at_ == bytes_.size();
  }

 private:
  void skipSpace() {
    while (at_ < bytes_.size() && std::isspace(static_cast<unsigned char>(bytes_[at_]))) ++at_;
  }
  [[noreturn]] void endsBefore(const std::string& what) const {
    if (partOfFile_) beyondPart();
    throwInputError(path_, "ends before its " + what);
  }
  // The header's numbers are read from the file's first part (they bound what is read whole);
  // one reaching its end may go on beyond it.
  [[noreturn]] void beyondPart() const {
    throwInputError(path_, "header runs past its first " + std::to_string(kHeaderPart) +
                               " bytes (at most that is read before its sizes are known)");
  }

  const std::string& path_;
  std::string_view bytes_;
  bool partOfFile_;
  std::size_t at_;
};

// One slice's RLE bytes into exactly `out.size()` samples.
void decodeRle(const std::string& where, std::string_view in, std::span<std::uint8_t> out) {
  std::size_t read = 0, made = 0;
  const auto next = [&]() -> std::uint8_t {
    if (read == in.size()) throwInputError(where, "ends inside a run");
    return std::uint8_t(in[read++]);
  };
  for (;;) {
    if (made == out.size() && read == in.size()) break;  // full, without the closing 0
    const std::uint8_t control = next();
    const std::size_t count = control & 0x7f;
    if (count == 0) break;
    if (count > out.size() - made) {
      throwInputError(
          where, "decodes to more than the " + std::to_string(out.size()) + " samples of a slice");
    }
    if (control & 0x80) {
      for (std::size_t i = 0; i < count; ++i) out[made++] = next();
    } else {
      const std::uint8_t value = next();
      for (std::size_t i = 0; i < count; ++i) out[made++] = value;
    }
  }
  if (made != out.size()) {
    throwInputError(where, "decodes to " + std::to_string(made) + " samples, " +
                               std::to_string(out.size()) + " expected");
  }
}

}  // namespace

Volume readSlc(const std::string& path, const LoadOptions& options) {
  // The header's numbers come first; the limits are checked on them before the rest is read.
  const std::uint64_t fileBytes = regularFileSize(path);
  // One byte beyond the part tells a number ending at its end from one going on past it.
  const std::uint64_t headBytes = std::min<std::uint64_t>(fileBytes, kHeaderPart + 1);
  const auto head = readFileBytes(path, 0, headBytes);
  SlcCursor header(path, std::string_view(reinterpret_cast<const char*>(head.data()), head.size()),
                   /*partOfFile=*/headBytes < fileBytes);
  if (header.integer("magic number") != kSlcMagic) {
    throwInputError(path, "is not a VolVis SLC file (its magic number is not 11111)");
  }
  glm::ivec3 dims;
  for (int a = 0; a < 3; ++a) {
    const std::int64_t size = header.integer("size");
    if (size < 1 || size > std::numeric_limits<int>::max()) {
      throwInputError(path, "size " + std::to_string(size) + " is not a positive int");
    }
    dims[a] = int(size);
  }
  const std::int64_t bits = header.integer("bits per voxel");
  if (bits != 8) {
    throwInputError(path, std::to_string(bits) + " bits per voxel: only 8 are read (as VTK)");
  }
  glm::dvec3 spacing;
  for (int a = 0; a < 3; ++a) spacing[a] = header.real("spacing");
  checkSpacing(path, "spacing", spacing);
  Volume volume = startVolume(path, dims, StoredType::UInt8, spacing, options);
  volume.format = "VolVis SLC";

  // The file is read whole once its sizes bound it: the header, an icon of at most kMaxIcon²
  // pixels, and per slice its size line and at most two bytes a sample (RLE's worst case).
  const std::uint64_t sliceSamples = std::uint64_t(dims.x) * std::uint64_t(dims.y);
  const std::uint64_t largest = kHeaderPart + 3 * std::uint64_t(kMaxIcon) * kMaxIcon +
                                std::uint64_t(dims.z) * (64 + 2 * sliceSamples + 1);
  if (fileBytes > largest) {
    throwInputError(path, "holds " + std::to_string(fileBytes) + " bytes, more than an SLC of " +
                              describeLayout(dims, StoredType::UInt8) + " can");
  }
  const std::string file = readWholeFile(path, fileBytes);
  SlcCursor cursor(path, file, /*partOfFile=*/false, header.offset());  // on from the spacing
  for (const char* skipped : {"units", "data origin", "data modification"}) cursor.token(skipped);
  const std::int64_t compression = cursor.integer("compression");
  if (compression != 0 && compression != 1) {
    throwInputError(path, "compression " + std::to_string(compression) +
                              " is neither 0 (none) nor 1 (run-length)");
  }
  const std::int64_t iconWidth = cursor.count("icon width");
  const std::int64_t iconHeight = cursor.count("icon height");
  if (iconWidth < 0 || iconHeight < 0 || iconWidth > kMaxIcon || iconHeight > kMaxIcon) {
    throwInputError(path, "icon size " + std::to_string(iconWidth) + " x " +
                              std::to_string(iconHeight) + " is not one");
  }
  cursor.marker("icon size");
  cursor.bytes(3 * std::uint64_t(iconWidth) * std::uint64_t(iconHeight), "the icon");

  SampleSink sink(path, volume, subsetOf(volume), StoredType::UInt8, /*bigEndian=*/false);
  std::vector<std::uint8_t> slice(static_cast<std::size_t>(sliceSamples));
  for (int z = 0; z < dims.z; ++z) {
    const std::string what = "slice " + std::to_string(z);
    if (compression == 0) {  // the samples alone, as vtkSLCReader reads them (no size line)
      const std::string_view bytes = cursor.bytes(sliceSamples, what);
      std::copy(bytes.begin(), bytes.end(), slice.begin());
    } else {
      const std::int64_t stored = cursor.count(what + "'s size");
      if (stored < 0)
        throwInputError(path, what + "'s size " + std::to_string(stored) + " is negative");
      cursor.marker(what + "'s size");
      decodeRle(path + ": " + what, cursor.bytes(std::uint64_t(stored), what), slice);
    }
    sink.put(std::uint64_t(z) * sliceSamples, slice);
  }
  if (!cursor.atEnd()) throwInputError(path, "holds bytes after its last slice");
  sink.finish();
  return volume;
}

}  // namespace vsil::io
