#pragma once
// Reading part of a volume: a box of voxel indices (--crop X0:X1,Y0:Y1,Z0:Z1) and every Nth
// sample along each axis (--stride N). Readers keep only these samples and, where the format
// allows, read only them (io/sample_sink.h).
#include <array>
#include <cstdint>
#include <optional>
#include <string>

#include <glm/glm.hpp>

namespace vsil {

// What was asked for, before a file's size is known. Ranges are half-open like Python slices
// and VTK extents' exclusive form: X0:X1 keeps x = X0 .. X1 - 1. An empty bound is the file's
// edge: "100:" is from 100 to the end, ":" the whole axis.
struct ReadRegion {
  struct Range {
    std::optional<int> begin;  // >= 0
    std::optional<int> end;    // > begin
  };
  std::optional<std::array<Range, 3>> crop;
  int stride = 1;        // >= 1: keep every stride-th sample along each axis, from the crop's start
  std::string cropText;  // --crop as given, for messages

  bool whole() const { return !crop && stride == 1; }
};

// What a read keeps of a file: along each axis, the samples lo + i·stride below hi.
struct VolumeSubset {
  glm::ivec3 fileDims{0};
  glm::ivec3 lo{0};
  glm::ivec3 hi{0};  // exclusive
  int stride = 1;

  glm::ivec3 dims() const {
    return glm::ivec3((glm::i64vec3(hi - lo) + std::int64_t(stride - 1)) / std::int64_t(stride));
  }
  bool whole() const { return lo == glm::ivec3(0) && hi == fileDims && stride == 1; }
  bool keeps(int axis, int i) const {
    return i >= lo[axis] && i < hi[axis] && (i - lo[axis]) % stride == 0;
  }
  int keptIndex(int axis, int i) const { return (i - lo[axis]) / stride; }
  // "X0:X1,Y0:Y1,Z0:Z1" with every bound written out.
  std::string cropText() const;
};

// The region resolved against a file's dims (which the caller has checked are positive). Throws
// InputError naming `where` and --crop when a range reaches beyond the file.
VolumeSubset resolveRegion(const std::string& where, glm::ivec3 fileDims, const ReadRegion& region);

}  // namespace vsil
