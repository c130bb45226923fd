#include "core/volume.h"

#include <algorithm>
#include <limits>

#include "core/error.h"

namespace vsil {

const char* sampleTypeName(SampleType type) {
  switch (type) {
    case SampleType::UInt8:
      return "uint8";
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
      return 1;
    case SampleType::UInt16:
      return 2;
    case SampleType::Int16:
      return 2;
    case SampleType::Float32:
      return 4;
  }
  return 0;
}

ValueRange valueRange(const Volume& volume) {
  if (volume.samples.empty()) return {};
  auto [lo, hi] = std::minmax_element(volume.samples.begin(), volume.samples.end());
  return {*lo, *hi};
}

void checkVolumeSize(const std::string& where, glm::ivec3 dims, const VolumeLimits& limits) {
  for (int axis = 0; axis < 3; ++axis) {
    if (dims[axis] <= 0) {
      throwInputError(where, "dimensions " + std::to_string(dims.x) + "x" + std::to_string(dims.y) +
                                 "x" + std::to_string(dims.z) + " are not all positive");
    }
    if (dims[axis] > limits.maxDimension) {
      throwInputError(where, "dimension " + std::to_string(dims[axis]) + " exceeds the limit of " +
                                 std::to_string(limits.maxDimension) + " samples per axis");
    }
  }
  // Each axis is at most maxDimension (<= 2^31), so the product of three fits 2^93: check in
  // long double first, then exactly.
  const long double bytes = (long double)dims.x * dims.y * dims.z * sizeof(float);
  if (bytes > (long double)limits.maxBytes) {
    throwInputError(where, "volume of " + std::to_string(dims.x) + "x" + std::to_string(dims.y) +
                               "x" + std::to_string(dims.z) + " samples needs " +
                               std::to_string((unsigned long long)(bytes / (1 << 20))) +
                               " MiB, over the memory limit of " +
                               std::to_string(limits.maxBytes >> 20) + " MiB");
  }
}

float defaultIso(const Volume& volume) {
  const ValueRange range = valueRange(volume);
  return float(0.5 * (double(range.min) + double(range.max)));
}

DerivedDefaults derivedDefaults(const Volume& volume) {
  const ValueRange range = valueRange(volume);
  return {.iso = defaultIso(volume), .valueRangeWidth = double(range.max) - double(range.min)};
}

}  // namespace vsil
