#include "core/volume.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <opencv2/imgproc.hpp>

#include "core/error.h"

namespace vsil {

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

// The samples quantized to 256 levels of the value range: every one up to 2^24, else a regular
// subsample of about that many (a second at 1024³ would be too long to wait for).
struct LevelHistogram {
  ValueRange range;
  double span = 0;  // range.max − range.min; the levels are span / 256 wide
  cv::Mat1b levels;
  std::array<std::size_t, kLevels> counts{};
  std::size_t total = 0;
  float valueAt(double level) const { return float(double(range.min) + level * span / kLevels); }
};

LevelHistogram levelHistogram(const Volume& volume, ValueRange range) {
  LevelHistogram h;
  h.range = range;
  h.span = double(h.range.max) - double(h.range.min);
  if (!(h.span > 0)) return h;
  const std::size_t count = volume.sampleCount();
  const std::size_t step = std::max<std::size_t>(1, count >> 24);
  h.levels.create(1, int((count + step - 1) / step));
  volume.visit([&](auto samples) {
    const double scale = kLevels / h.span;
    for (std::size_t i = 0, j = 0; i < samples.size(); i += step, ++j) {
      const double level = std::floor((double(samples[i]) - h.range.min) * scale);
      h.levels(0, int(j)) = std::uint8_t(std::clamp(level, 0.0, kLevels - 1.0));
      ++h.counts[h.levels(0, int(j))];
    }
  });
  h.total = std::size_t(h.levels.cols);
  return h;
}

float otsuThreshold(const LevelHistogram& h) {
  if (!(h.span > 0)) return h.range.min;
  cv::Mat1b binary;
  const int t = int(cv::threshold(h.levels, binary, 0, 255, cv::THRESH_BINARY | cv::THRESH_OTSU));
  // Otsu puts levels <= t in the lower class. Where no sample lies between the two classes,
  // every threshold in that gap splits them alike: take the gap's middle (0.5 for a 0/1 mask,
  // where the first such t, OpenCV's choice, would be the bottom of the gap).
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
  const double span = double(range.max) - double(range.min);
  if (!(span > 0)) return counts;
  const std::size_t sliceSize = std::size_t(volume.dims.x) * std::size_t(volume.dims.y);
  volume.visit([&](auto samples) {
    const double scale = kLevels / span;
    for (std::size_t i = std::size_t(zBegin) * sliceSize; i < std::size_t(zEnd) * sliceSize; ++i) {
      const double level = std::floor((double(samples[i]) - range.min) * scale);
      ++counts[std::size_t(std::clamp(level, 0.0, kLevels - 1.0))];
    }
  });
  return counts;
}

DerivedDefaults derivedDefaultsFromCounts(ValueRange range, const LevelCounts& counts) {
  LevelHistogram h;
  h.range = range;
  h.span = double(range.max) - double(range.min);
  if (h.span > 0) {
    // Otsu (cv::threshold) reads only the histogram of its image: the levels in order.
    std::size_t total = 0;
    for (std::size_t c : counts) total += c;
    h.levels.create(1, int(total));
    int j = 0;
    for (int level = 0; level < kLevels; ++level) {
      h.counts[std::size_t(level)] = counts[std::size_t(level)];
      for (std::uint64_t k = 0; k < counts[std::size_t(level)]; ++k)
        h.levels(0, j++) = std::uint8_t(level);
    }
    h.total = total;
  }
  const float iso = otsuThreshold(h);
  return {.iso = iso,
          .valueRangeWidth = h.span,
          .valueMin = h.range.min,
          .windowHigh = std::max(quantileAbove(h, iso, kDefaultWindowQuantile), iso)};
}

DerivedDefaults derivedDefaults(const Volume& volume, ValueRange range) {
  const LevelHistogram h = levelHistogram(volume, range);
  const float iso = otsuThreshold(h);
  return {.iso = iso,
          .valueRangeWidth = h.span,
          .valueMin = h.range.min,
          .windowHigh = std::max(quantileAbove(h, iso, kDefaultWindowQuantile), iso)};
}

}  // namespace vsil
