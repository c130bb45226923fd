#include "io/sample_sink.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <type_traits>

#include "core/error.h"
#include "core/options.h"

namespace vsil::io {
namespace {

template <typename Unsigned>
Unsigned byteSwapped(Unsigned value) {
  Unsigned swapped = 0;
  for (std::size_t i = 0; i < sizeof(Unsigned); ++i) {
    swapped = Unsigned((swapped << 8) | ((value >> (8 * i)) & 0xff));
  }
  return swapped;
}

// The file's sample at `p` as its own C++ type.
template <typename FileC>
FileC load(const std::uint8_t* p, bool swap) {
  using Bits = std::conditional_t<
      sizeof(FileC) == 1, std::uint8_t,
      std::conditional_t<sizeof(FileC) == 2, std::uint16_t,
                         std::conditional_t<sizeof(FileC) == 4, std::uint32_t, std::uint64_t>>>;
  Bits bits;
  std::memcpy(&bits, p, sizeof bits);
  if (swap) bits = byteSwapped(bits);
  return std::bit_cast<FileC>(bits);
}

[[noreturn]] void badSample(const std::string& where, std::uint64_t index,
                            const std::string& what) {
  throwInputError(where, "sample " + std::to_string(index) + " " + what);
}

// Whether float32 `kept` holds the integer `value` exactly (every integer up to 2^24 does).
// Compared as integers: the float of a 64-bit value may be 2^63 or 2^64, beyond its type.
template <typename Integer>
bool exactInFloat32(Integer value, float kept) {
  if constexpr (sizeof(Integer) <= 4) {
    return std::int64_t(kept) == std::int64_t(value);
  } else {
    const double bound = std::is_signed_v<Integer> ? 0x1p63 : 0x1p64;
    return double(kept) < bound && Integer(kept) == value;
  }
}

// `count` file samples of the 32- or 64-bit integer type `Integer` into floats; returns how
// many float32 rounded.
template <typename Integer>
std::uint64_t convertWideIntegers(float* out, const std::uint8_t* in, std::size_t inStep,
                                  std::size_t count, bool swap) {
  std::uint64_t inexact = 0;
  for (std::size_t i = 0; i < count; ++i, in += inStep) {
    const Integer value = load<Integer>(in, swap);
    out[i] = float(value);
    inexact += !exactInFloat32(value, out[i]);
  }
  return inexact;
}

// Calls f(T{}) with the C++ type T that holds one stored sample of `type`.
template <typename F>
decltype(auto) withStoredCType(StoredType type, F&& f) {
  switch (type) {
    case StoredType::UInt8:
      return f(std::uint8_t{});
    case StoredType::Int8:
      return f(std::int8_t{});
    case StoredType::UInt16:
      return f(std::uint16_t{});
    case StoredType::Int16:
      return f(std::int16_t{});
    case StoredType::Int32:
      return f(std::int32_t{});
    case StoredType::UInt32:
      return f(std::uint32_t{});
    case StoredType::Int64:
      return f(std::int64_t{});
    case StoredType::UInt64:
      return f(std::uint64_t{});
    case StoredType::Float32:
      return f(float{});
    case StoredType::Float64:
      return f(double{});
  }
  throw std::logic_error("withStoredCType: not a StoredType");
}

}  // namespace

void checkFinite(const std::string& where, std::uint64_t index, double value) {
  if (std::isnan(value)) badSample(where, index, "is NaN");
  if (std::isinf(value)) badSample(where, index, "is infinite");
}

void checkFloat32(const std::string& where, std::uint64_t index, double value, const char* what) {
  checkFinite(where, index, value);
  if (std::abs(value) > double(std::numeric_limits<float>::max())) {
    badSample(where, index, what + ("(" + formatNumber(value) + ") is beyond the float32 range"));
  }
}

SampleSink::SampleSink(const std::string& where, Volume& volume, const VolumeSubset& subset,
                       StoredType fileType, bool bigEndian, Rescale rescale)
    : where_(where),
      volume_(volume),
      subset_(subset),
      fileType_(fileType),
      swap_(bigEndian != (std::endian::native == std::endian::big)),
      rescale_(rescale),
      size_(storedSize(fileType)),
      fileSamples_(std::uint64_t(subset.fileDims.x) * std::uint64_t(subset.fileDims.y) *
                   std::uint64_t(subset.fileDims.z)),
      whole_(subset.whole()) {
  if (volume.type() != keptSampleType(fileType, rescale) || volume.dims != subset.dims() ||
      volume.sampleCount() != volume.voxelCount()) {
    throw std::logic_error("SampleSink: the volume is not allocated for the subset");
  }
  if (size_ == 1) swap_ = false;
}

std::uint64_t SampleSink::neededBytes() const {
  const glm::ivec3 kept = subset_.dims();
  const std::uint64_t rowSamples = std::uint64_t(subset_.hi.x - 1 - subset_.lo.x) /
                                       std::uint64_t(subset_.stride) * subset_.stride +
                                   1;
  return std::uint64_t(kept.y) * std::uint64_t(kept.z) * rowSamples * size_;
}

bool SampleSink::rowKept(std::uint64_t row) const {
  const auto fy = std::uint64_t(subset_.fileDims.y);
  return subset_.keeps(1, int(row % fy)) && subset_.keeps(2, int(row / fy));
}

template <typename FileC>
void SampleSink::decodeViaDouble(float* out, const std::uint8_t* in, std::size_t inStep,
                                 std::size_t count, std::uint64_t firstSample) {
  const bool rescaled = !rescale_.identity();  // else the stored value as is (-0 stays -0)
  const char* what = rescaled ? "rescaled " : "";
  std::uint64_t inexact = 0;
  for (std::size_t i = 0; i < count; ++i, in += inStep) {
    const double stored = double(load<FileC>(in, swap_));
    const double value = rescaled ? rescale_.slope * stored + rescale_.intercept : stored;
    checkFloat32(where_, firstSample + i * subset_.stride, value, what);
    out[i] = float(value);
    inexact += double(out[i]) != value;
  }
  if (inexact) inexact_ += inexact;
}

template <typename Out>
void SampleSink::decode(Out* out, const std::uint8_t* in, std::size_t inStep, std::size_t count,
                        std::uint64_t firstSample) {
  if constexpr (std::is_same_v<Out, float>) {
    if (!rescale_.identity() || fileType_ == StoredType::Float64) {
      return withStoredCType(fileType_, [&](auto sample) {
        decodeViaDouble<decltype(sample)>(out, in, inStep, count, firstSample);
      });
    }
    if (isWideInteger(fileType_)) {
      const std::uint64_t inexact = withStoredCType(fileType_, [&](auto sample) -> std::uint64_t {
        using Integer = decltype(sample);
        if constexpr (std::is_integral_v<Integer> && sizeof(Integer) >= 4) {
          return convertWideIntegers<Integer>(out, in, inStep, count, swap_);
        } else {
          throw std::logic_error("SampleSink: not a wide integer type");
        }
      });
      if (inexact) inexact_ += inexact;
      return;
    }
  }
  if (!swap_ && inStep == sizeof(Out)) {
    std::memcpy(out, in, count * sizeof(Out));
  } else {
    for (std::size_t i = 0; i < count; ++i, in += inStep) out[i] = load<Out>(in, swap_);
  }
  if constexpr (std::is_same_v<Out, float>) {
    for (std::size_t i = 0; i < count; ++i) {
      if (!std::isfinite(out[i])) checkFinite(where_, firstSample + i * subset_.stride, out[i]);
    }
  }
}

void SampleSink::decodeRun(std::size_t keptIndex, const std::uint8_t* in, std::size_t inStep,
                           std::size_t count, std::uint64_t firstSample) {
  volume_.visit(
      [&](auto samples) { decode(samples.data() + keptIndex, in, inStep, count, firstSample); });
}

void SampleSink::put(std::uint64_t firstSample, std::span<const std::uint8_t> bytes) {
  std::uint64_t count = bytes.size() / size_;
  if (firstSample > fileSamples_ || count > fileSamples_ - firstSample) {
    throw std::logic_error("SampleSink::put: samples beyond the file's");
  }
  const std::uint8_t* in = bytes.data();
  if (whole_) {
    decodeRun(std::size_t(firstSample), in, size_, std::size_t(count), firstSample);
    return;
  }
  const auto fx = std::uint64_t(subset_.fileDims.x);
  const std::uint64_t stride = std::uint64_t(subset_.stride);
  const auto lo = std::uint64_t(subset_.lo.x), hi = std::uint64_t(subset_.hi.x);
  std::uint64_t sample = firstSample;
  while (count > 0) {
    const std::uint64_t x = sample % fx, row = sample / fx;
    const std::uint64_t segment = std::min(count, fx - x);
    if (rowKept(row)) {
      std::uint64_t first = std::max(x, lo);
      if (const std::uint64_t offset = (first - lo) % stride) first += stride - offset;
      const std::uint64_t last = std::min(x + segment, hi);  // exclusive
      if (first < last) {
        const std::uint64_t fy = std::uint64_t(subset_.fileDims.y);
        const std::size_t kept =
            volume_.index(int((first - lo) / stride), subset_.keptIndex(1, int(row % fy)),
                          subset_.keptIndex(2, int(row / fy)));
        decodeRun(kept, in + (first - x) * size_, std::size_t(stride * size_),
                  std::size_t((last - first + stride - 1) / stride), sample + (first - x));
      }
    }
    sample += segment;
    in += segment * size_;
    count -= segment;
  }
}

void SampleSink::Appender::append(std::span<const std::uint8_t> bytes) {
  const std::size_t size = sink_.size_;
  if (!partial_.empty()) {
    const std::size_t take = std::min(size - partial_.size(), bytes.size());
    partial_.insert(partial_.end(), bytes.begin(), bytes.begin() + std::ptrdiff_t(take));
    bytes = bytes.subspan(take);
    if (partial_.size() < size) return;
    sink_.put(next_++, partial_);
    partial_.clear();
  }
  const std::size_t whole = bytes.size() / size * size;
  if (whole) {
    sink_.put(next_, bytes.first(whole));
    next_ += whole / size;
  }
  partial_.assign(bytes.begin() + std::ptrdiff_t(whole), bytes.end());
}

void SampleSink::putValue(std::uint64_t index, double value) {
  std::size_t kept = 0;
  if (whole_) {
    kept = std::size_t(index);
  } else {
    const auto fx = std::uint64_t(subset_.fileDims.x), fy = std::uint64_t(subset_.fileDims.y);
    const int x = int(index % fx), y = int(index / fx % fy), z = int(index / fx / fy);
    if (!subset_.keeps(0, x) || !subset_.keeps(1, y) || !subset_.keeps(2, z)) return;
    kept = volume_.index(subset_.keptIndex(0, x), subset_.keptIndex(1, y), subset_.keptIndex(2, z));
  }
  const bool rescaled = !rescale_.identity();
  if (rescaled) {
    value = rescale_.slope * value + rescale_.intercept;
    checkFloat32(where_, index, value, "rescaled ");
  }
  volume_.visit([&](auto samples) {
    using Out = typename decltype(samples)::value_type;
    samples[kept] = Out(value);
    if constexpr (std::is_same_v<Out, float>) {
      if ((rescaled || fileType_ == StoredType::Float64 || isWideInteger(fileType_)) &&
          double(samples[kept]) != value) {
        ++inexact_;
      }
    }
  });
}

void SampleSink::forEachRun(
    std::uint64_t maxBytes,
    const std::function<void(std::uint64_t firstSample, std::uint64_t count)>& f) const {
  const std::uint64_t maxSamples = std::max<std::uint64_t>(1, maxBytes / size_);
  const glm::u64vec3 fileDims(subset_.fileDims);
  const auto stride = std::uint64_t(subset_.stride);
  // Each kept row from its first to its last kept sample.
  const std::uint64_t rowSamples =
      (std::uint64_t(subset_.hi.x - 1 - subset_.lo.x) / stride) * stride + 1;
  std::uint64_t runStart = 0, runCount = 0;
  auto emit = [&] {
    for (std::uint64_t done = 0; done < runCount;) {
      const std::uint64_t count = std::min(maxSamples, runCount - done);
      f(runStart + done, count);
      done += count;
    }
    runCount = 0;
  };
  for (int z = subset_.lo.z; z < subset_.hi.z; z += subset_.stride) {
    for (int y = subset_.lo.y; y < subset_.hi.y; y += subset_.stride) {
      const std::uint64_t start =
          (std::uint64_t(z) * fileDims.y + std::uint64_t(y)) * fileDims.x + subset_.lo.x;
      if (runCount && runStart + runCount == start && runCount + rowSamples <= maxSamples) {
        runCount += rowSamples;
      } else {
        emit();
        runStart = start;
        runCount = rowSamples;
      }
    }
  }
  emit();
}

void SampleSink::finishAppending() {
  if (appender_.nextSample() != fileSamples_ || appender_.withinSample()) {
    throw std::logic_error("SampleSink: " + std::to_string(appender_.nextSample()) + " of " +
                           std::to_string(fileSamples_) + " samples appended");
  }
  finish();
}

void SampleSink::finish() {
  volume_.inexactSamples = inexact_;
  if (inexact_ > 0) {
    volume_.warnings.push_back(
        where_ + ": " + std::to_string(inexact_) + " of " + std::to_string(volume_.voxelCount()) +
        " samples lost precision as float32 (the file's " + storedTypeName(fileType_) +
        (rescale_.identity() ? std::string() : ", rescaled") + ")");
  }
}

}  // namespace vsil::io
