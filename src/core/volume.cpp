#include "core/volume.h"

#include <sys/mman.h>

#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <limits>
#include <new>
#include <span>
#include <type_traits>

#include "core/error.h"

namespace vsil {

namespace {
// Smaller volumes stay in a vector, and every volume under AddressSanitizer, whose redzones
// around heap blocks catch a reader writing past the samples.
#if defined(__SANITIZE_ADDRESS__)
constexpr std::size_t kPopulatedBytes = SIZE_MAX;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr std::size_t kPopulatedBytes = SIZE_MAX;
#else
constexpr std::size_t kPopulatedBytes = std::size_t(1) << 20;
#endif
#else
constexpr std::size_t kPopulatedBytes = std::size_t(1) << 20;
#endif
}  // namespace

const char* sampleTypeName(SampleType type) {
  switch (type) {
    case SampleType::UInt8:
      return "uint8";
    case SampleType::Int8:
      return "int8";
    case SampleType::UInt16:
      return "uint16";
    case SampleType::Int16:
      return "int16";
    case SampleType::Float32:
      return "float32";
  }
  return "unknown";
}

std::size_t sampleTypeSize(SampleType type) {
  switch (type) {
    case SampleType::UInt8:
    case SampleType::Int8:
      return 1;
    case SampleType::UInt16:
    case SampleType::Int16:
      return 2;
    case SampleType::Float32:
      return 4;
  }
  return 0;
}

bool isIntegerType(SampleType type) {
  return type != SampleType::Float32;
}

void Volume::allocate(SampleType type) {
  const std::size_t count = voxelCount();
  // Large volumes take their zeroed pages from the kernel in one call (MAP_POPULATE); a
  // vector's zero fill faults them in one at a time, about 1 ms per MB more on 2 cores.
  if (const std::size_t bytes = count * sampleTypeSize(type); bytes >= kPopulatedBytes) {
    void* start = ::mmap(nullptr, bytes, PROT_READ | PROT_WRITE,
                         MAP_PRIVATE | MAP_ANONYMOUS | MAP_POPULATE, -1, 0);
    if (start == MAP_FAILED) throw std::bad_alloc();
    allocateIn(type, std::shared_ptr<void>(start, [bytes](void* p) { ::munmap(p, bytes); }));
    return;
  }
  switch (type) {
    case SampleType::UInt8:
      samples_.emplace<SampleBuffer<std::uint8_t>>(count);
      break;
    case SampleType::Int8:
      samples_.emplace<SampleBuffer<std::int8_t>>(count);
      break;
    case SampleType::UInt16:
      samples_.emplace<SampleBuffer<std::uint16_t>>(count);
      break;
    case SampleType::Int16:
      samples_.emplace<SampleBuffer<std::int16_t>>(count);
      break;
    case SampleType::Float32:
      samples_.emplace<SampleBuffer<float>>(count);
      break;
  }
}

void Volume::allocateIn(SampleType type, std::shared_ptr<void> memory) {
  void* start = memory.get();
  const auto place = [&]<typename C>(C*) {
    samples_.emplace<SampleBuffer<C>>(static_cast<C*>(start), voxelCount(), std::move(memory),
                                      false);
  };
  switch (type) {
    case SampleType::UInt8:
      return place(static_cast<std::uint8_t*>(nullptr));
    case SampleType::Int8:
      return place(static_cast<std::int8_t*>(nullptr));
    case SampleType::UInt16:
      return place(static_cast<std::uint16_t*>(nullptr));
    case SampleType::Int16:
      return place(static_cast<std::int16_t*>(nullptr));
    case SampleType::Float32:
      return place(static_cast<float*>(nullptr));
  }
}

Volume Volume::sharing(const std::shared_ptr<Volume>& owner) {
  // Copy every field but the samples: move them out for the copy, then back.
  SampleStorage samples = std::move(owner->samples_);
  owner->samples_ = SampleStorage();
  Volume view = *owner;
  owner->samples_ = std::move(samples);
  owner->visit([&](auto span) { view.borrow(span.data(), owner); });
  return view;
}

std::size_t Volume::sampleCount() const {
  return std::visit([](const auto& samples) { return samples.size(); }, samples_);
}

ValueRange valueRange(const Volume& volume) {
  return volume.visit([](auto samples) -> ValueRange {
    if (samples.empty()) return {};
    const auto [lo, hi] = std::minmax_element(samples.begin(), samples.end());
    return {float(*lo), float(*hi)};
  });
}

namespace {

std::string dimsText(glm::ivec3 dims) {
  return std::to_string(dims.x) + "x" + std::to_string(dims.y) + "x" + std::to_string(dims.z);
}

void checkDims(const std::string& where, glm::ivec3 dims, int maxDimension) {
  for (int axis = 0; axis < 3; ++axis) {
    if (dims[axis] <= 0) {
      throwInputError(where, "dimensions " + dimsText(dims) + " are not all positive");
    }
  }
  for (int axis = 0; axis < 3; ++axis) {
    if (dims[axis] > maxDimension) {
      throwInputError(where, "dimension " + std::to_string(dims[axis]) + " exceeds the limit of " +
                                 std::to_string(maxDimension) + " samples per axis");
    }
  }
}

}  // namespace

VolumeSubset planVolume(const std::string& where, glm::ivec3 fileDims, SampleType type,
                        const VolumeLimits& limits, const ReadRegion& region) {
  // Without a region the file's dims are the volume's and must be within the limits; with one,
  // only what is kept must be, and the file may be larger (up to 2^40 samples per axis product
  // of bytes, so that every size computed from them fits 64 bits).
  if (region.whole()) {
    checkDims(where, fileDims, limits.maxDimension);
  } else {
    checkDims(where, fileDims, std::numeric_limits<int>::max());
    const long double fileBytes = (long double)fileDims.x * fileDims.y * fileDims.z * 8;
    if (fileBytes > (long double)(std::uint64_t(1) << 62)) {
      throwInputError(where, "dimensions " + dimsText(fileDims) + " are too large for any file");
    }
  }
  const VolumeSubset subset = resolveRegion(where, fileDims, region);
  const glm::ivec3 dims = subset.dims();
  if (!region.whole()) {
    for (int axis = 0; axis < 3; ++axis) {
      if (dims[axis] > limits.maxDimension) {
        throwInputError(where, std::string(region.crop ? "--crop" : "--stride") + " keeps " +
                                   dimsText(dims) + " samples; " + std::to_string(dims[axis]) +
                                   " exceeds the limit of " + std::to_string(limits.maxDimension) +
                                   " samples per axis");
      }
    }
  }
  // Each kept axis is at most maxDimension (<= 2^31), so the product of three fits 2^93: count in
  // long double first, then exactly.
  const long double samples = (long double)dims.x * dims.y * dims.z * sampleTypeSize(type);
  std::uint64_t bytes = std::numeric_limits<std::uint64_t>::max();
  if (samples < 1e18L) {  // task bytes are a few times the samples' bytes: no overflow
    bytes = std::uint64_t(dims.x) * std::uint64_t(dims.y) * std::uint64_t(dims.z) *
            sampleTypeSize(type);
    if (limits.taskBytes) bytes = limits.taskBytes(dims, type);
  }
  const std::string what = limits.task + " " + dimsText(dims) + " " + sampleTypeName(type) +
                           " samples" + limits.taskDetail;
  const std::string options = "; read less with --crop X0:X1,Y0:Y1,Z0:Z1 or --stride N";
  if (bytes > limits.maxBytes) {
    const auto mib = [](std::uint64_t b) {
      return b == std::numeric_limits<std::uint64_t>::max()
                 ? std::string("more than 2^64 bytes")
                 : std::to_string((b + (1u << 20) - 1) >> 20) + " MiB";
    };
    throwInputError(where, what + " needs " + mib(bytes) + ", over the --max-memory limit of " +
                               std::to_string(limits.maxBytes >> 20) + " MiB" + options +
                               ", or raise --max-memory");
  }
  return subset;
}

namespace {

constexpr int kLevels = 256;

// The level of a sample value: floor((v − min)·256/span), clamped to 0..255.
std::uint8_t levelOf(double value, double min, double scale) {
  return std::uint8_t(std::clamp(std::floor((value - min) * scale), 0.0, kLevels - 1.0));
}

// Adds the samples [begin, end), every `step`-th, to `counts` in 256 levels of `range` (span
// > 0). Samples of 8- and 16-bit types take their level from a table of every value of the type
// built with levelOf: the same levels, without a floor per sample (the histogram of a default
// render: bonsai 74 → 20 ms CPU, see the startup table in the README).
template <typename T>
void countLevels(std::span<const T> samples, std::size_t begin, std::size_t end, std::size_t step,
                 ValueRange range, LevelCounts& counts) {
  const double scale = kLevels / (double(range.max) - double(range.min));
  if constexpr (std::is_integral_v<T> && sizeof(T) <= 2) {
    using Unsigned = std::make_unsigned_t<T>;
    std::array<std::uint8_t, std::size_t(std::numeric_limits<Unsigned>::max()) + 1> table;
    for (std::size_t u = 0; u < table.size(); ++u) {
      table[u] = levelOf(double(T(Unsigned(u))), range.min, scale);
    }
    for (std::size_t i = begin; i < end; i += step) ++counts[table[Unsigned(samples[i])]];
  } else {
    for (std::size_t i = begin; i < end; i += step) {
      ++counts[levelOf(double(samples[i]), range.min, scale)];
    }
  }
}

// The samples quantized to 256 levels of the value range: every one up to 2^24, else a regular
// subsample of about that many (a second at 1024³ would be too long to wait for).
struct LevelHistogram {
  ValueRange range;
  double span = 0;  // range.max − range.min; the levels are span / 256 wide
  LevelCounts counts{};
  std::uint64_t total = 0;
  float valueAt(double level) const { return float(double(range.min) + level * span / kLevels); }
};

LevelHistogram levelHistogram(const Volume& volume, ValueRange range) {
  LevelHistogram h;
  h.range = range;
  h.span = double(h.range.max) - double(h.range.min);
  if (!(h.span > 0)) return h;
  const std::size_t count = volume.sampleCount();
  const std::size_t step = std::max<std::size_t>(1, count >> 24);
  volume.visit([&](auto samples) {
    countLevels(std::span<const typename decltype(samples)::element_type>(samples), 0,
                samples.size(), step, range, h.counts);
  });
  h.total = (count + step - 1) / step;
  return h;
}

}  // namespace

int otsuLevel(const LevelCounts& counts, std::uint64_t total) {
  const double scale = 1.0 / double(total);
  double mean = 0;
  for (int level = 0; level < kLevels; ++level) mean += level * double(counts[level]);
  mean *= scale;
  double q1 = 0, mean1 = 0, best = 0;
  int threshold = 0;
  for (int level = 0; level < kLevels; ++level) {
    const double p = double(counts[level]) * scale;
    mean1 *= q1;
    q1 += p;
    const double q2 = 1.0 - q1;
    if (std::min(q1, q2) < FLT_EPSILON || std::max(q1, q2) > 1.0 - FLT_EPSILON) continue;
    mean1 = (mean1 + level * p) / q1;
    const double mean2 = (mean - q1 * mean1) / q2;
    const double between = q1 * q2 * (mean1 - mean2) * (mean1 - mean2);
    if (between > best) {
      best = between;
      threshold = level;
    }
  }
  return threshold;
}

namespace {

float otsuThreshold(const LevelHistogram& h) {
  if (!(h.span > 0)) return h.range.min;
  const int t = otsuLevel(h.counts, h.total);
  // Otsu puts levels <= t in the lower class. Where no sample lies between the two classes,
  // every threshold in that gap splits them alike: take the gap's middle (0.5 for a 0/1 mask,
  // where the first such t, Otsu's choice, would be the bottom of the gap).
  int below = t, above = t + 1;
  while (below > 0 && h.counts[below] == 0) --below;
  while (above < kLevels - 1 && h.counts[above] == 0) ++above;
  return h.valueAt(0.5 * ((below + 1) + above));  // in units of span / kLevels
}

// The top of the level holding the `fraction` quantile of the samples above `low`; the range's
// maximum where none lies above it.
float quantileAbove(const LevelHistogram& h, float low, double fraction) {
  if (!(h.span > 0)) return h.range.max;
  const int first =
      std::clamp(int(std::floor((double(low) - h.range.min) * kLevels / h.span)) + 1, 0, kLevels);
  std::size_t above = 0;
  for (int level = first; level < kLevels; ++level) above += h.counts[level];
  if (above == 0) return h.range.max;
  const double wanted = fraction * double(above);
  std::size_t seen = 0;
  for (int level = first; level < kLevels; ++level) {
    seen += h.counts[level];
    if (double(seen) >= wanted) return std::min(h.range.max, h.valueAt(level + 1));
  }
  return h.range.max;
}

// The default window's top: above Otsu's threshold `iso` even where nothing lies above it (a
// constant volume), by a thousandth of the value range or one data unit, so that the window is
// one --window takes (LO < HI) and --meta-out's parameters replay. The picture is the same:
// values at or below LO show nothing.
float defaultWindowHigh(const LevelHistogram& h, float iso) {
  const float high = quantileAbove(h, iso, kDefaultWindowQuantile);
  if (high > iso) return high;
  const float above = iso + float(h.span > 0 ? h.span / 1000.0 : 1.0);
  return above > iso ? above : std::nextafter(iso, std::numeric_limits<float>::infinity());
}

}  // namespace

float defaultIso(const Volume& volume) {
  return defaultIso(volume, valueRange(volume));
}

float defaultIso(const Volume& volume, ValueRange range) {
  return otsuThreshold(levelHistogram(volume, range));
}

DerivedDefaults derivedDefaults(const Volume& volume) {
  return derivedDefaults(volume, valueRange(volume));
}

LevelCounts levelCounts(const Volume& volume, ValueRange range, int zBegin, int zEnd) {
  LevelCounts counts{};
  if (!(double(range.max) - double(range.min) > 0)) return counts;
  const std::size_t sliceSize = std::size_t(volume.dims.x) * std::size_t(volume.dims.y);
  volume.visit([&](auto samples) {
    countLevels(std::span<const typename decltype(samples)::element_type>(samples),
                std::size_t(zBegin) * sliceSize, std::size_t(zEnd) * sliceSize, 1, range, counts);
  });
  return counts;
}

DerivedDefaults derivedDefaultsFromCounts(ValueRange range, const LevelCounts& counts) {
  LevelHistogram h;
  h.range = range;
  h.span = double(range.max) - double(range.min);
  if (h.span > 0) {
    h.counts = counts;
    for (std::uint64_t c : counts) h.total += c;
  }
  const float iso = otsuThreshold(h);
  return {.iso = iso,
          .valueRangeWidth = h.span,
          .valueMin = h.range.min,
          .windowHigh = defaultWindowHigh(h, iso)};
}

DerivedDefaults derivedDefaults(const Volume& volume, ValueRange range) {
  const LevelHistogram h = levelHistogram(volume, range);
  const float iso = otsuThreshold(h);
  return {.iso = iso,
          .valueRangeWidth = h.span,
          .valueMin = h.range.min,
          .windowHigh = defaultWindowHigh(h, iso)};
}

}  // namespace vsil
