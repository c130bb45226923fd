#pragma once
// A scalar volume on a regular grid: the single in-memory form every reader and generator
// produces and every technique consumes.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/limits.h"
#include "core/options.h"

namespace vsil {

// The type of the samples in the file (what the user's --iso units mean). In memory every
// sample is a float in the data's own units: exact for all four types.
enum class SampleType { UInt8, UInt16, Int16, Float32 };

const char* sampleTypeName(SampleType type);
std::size_t sampleTypeSize(SampleType type);

struct Volume {
  std::string name;    // dataset name: a file's base name without extension, or the generator's
  std::string source;  // the path or generator spec it was made from
  glm::ivec3 dims{0};  // samples along x (fastest in memory), y, z
  glm::dvec3 spacing{1.0};  // distance between sample centres along x, y, z (any unit)
  SampleType type = SampleType::UInt8;
  std::vector<float> samples;  // dims.x*dims.y*dims.z values, x fastest, then y, then z

  std::size_t voxelCount() const {
    return std::size_t(dims.x) * std::size_t(dims.y) * std::size_t(dims.z);
  }
  std::size_t index(int x, int y, int z) const {
    return (std::size_t(z) * std::size_t(dims.y) + std::size_t(y)) * std::size_t(dims.x) +
           std::size_t(x);
  }
  float at(int x, int y, int z) const { return samples[index(x, y, z)]; }
};

struct ValueRange {
  float min = 0.0f;
  float max = 0.0f;
};
ValueRange valueRange(const Volume& volume);

// The iso value a technique uses when none is given: the middle of the value range.
float defaultIso(const Volume& volume);

// The facts option defaults are derived from (core/options.h), for this volume.
DerivedDefaults derivedDefaults(const Volume& volume);

// Limits checked before anything is allocated. maxBytes bounds the in-memory volume
// (4 bytes per sample; default: half the physical memory, core/limits.h); maxDimension bounds
// each axis (the GL 3D texture limit, 2048).
struct VolumeLimits {
  std::size_t maxBytes = limits::defaultMemoryBytes();
  int maxDimension = limits::kMaxVolumeSide;
};

// Throws InputError naming `where` when dims are not positive, exceed the limits, or the
// in-memory size would overflow or exceed maxBytes.
void checkVolumeSize(const std::string& where, glm::ivec3 dims, const VolumeLimits& limits);

}  // namespace vsil
