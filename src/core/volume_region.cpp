#include "core/volume_region.h"

#include "core/error.h"

namespace vsil {

std::string VolumeSubset::cropText() const {
  std::string text;
  for (int axis = 0; axis < 3; ++axis) {
    if (axis) text += ",";
    text += std::to_string(lo[axis]) + ":" + std::to_string(hi[axis]);
  }
  return text;
}

VolumeSubset resolveRegion(const std::string& where, glm::ivec3 fileDims,
                           const ReadRegion& region) {
  VolumeSubset subset;
  subset.fileDims = fileDims;
  subset.hi = fileDims;
  subset.stride = region.stride;
  if (!region.crop) return subset;
  static const char* kAxes[] = {"x", "y", "z"};
  for (int axis = 0; axis < 3; ++axis) {
    const ReadRegion::Range& range = (*region.crop)[std::size_t(axis)];
    const int begin = range.begin.value_or(0);
    const int end = range.end.value_or(fileDims[axis]);
    const std::string flag = "--crop '" + region.cropText + "'";
    const std::string samples = std::to_string(fileDims[axis]) +
                                (fileDims[axis] == 1 ? " sample" : " samples") + " along " +
                                kAxes[axis];
    if (end > fileDims[axis]) {
      throwInputError(where, flag + " ends at " + kAxes[axis] + " = " + std::to_string(end) +
                                 ", beyond the volume's " + samples);
    }
    if (begin >= end) {
      throwInputError(where, flag + " starts at " + kAxes[axis] + " = " + std::to_string(begin) +
                                 ", leaving nothing of the volume's " + samples);
    }
    subset.lo[axis] = begin;
    subset.hi[axis] = end;
  }
  return subset;
}

}  // namespace vsil
