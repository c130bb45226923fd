#include "analytic_volumes.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace vsil::test {

namespace {

// f = clamp01(0.5 + insideDistance(p) / ramp) at every voxel p: f = 0.5 exactly where the signed
// distance (positive inside) is zero.
template <typename InsideDistance>
Volume rampVolume(const char* name, glm::ivec3 dims, double ramp, InsideDistance insideDistance) {
  Volume volume;
  volume.name = name;
  volume.source = std::string("test:") + name;
  volume.dims = dims;
  volume.allocate(SampleType::Float32);
  const std::span<float> samples = volume.samples<float>();
  for (int z = 0; z < dims.z; ++z) {
    for (int y = 0; y < dims.y; ++y) {
      for (int x = 0; x < dims.x; ++x) {
        const double d = insideDistance(glm::dvec3(x, y, z));
        samples[volume.index(x, y, z)] = float(std::clamp(0.5 + d / ramp, 0.0, 1.0));
      }
    }
  }
  return volume;
}

}  // namespace

Volume ballsVolume(glm::ivec3 dims, const std::vector<Ball>& balls, double ramp) {
  // The largest inside distance over the balls: the clamped ramp is increasing, so this is the
  // maximum of the balls' own ramps.
  return rampVolume("balls", dims, ramp, [&](glm::dvec3 p) {
    double d = -std::numeric_limits<double>::infinity();
    for (const Ball& ball : balls) {
      d = std::max(d, ball.radiusVoxels - glm::length(p - ball.centreVoxel));
    }
    return d;
  });
}

Volume cylinderVolume(glm::ivec3 dims, const Cylinder& cylinder, double ramp) {
  const glm::dvec3 axis = glm::normalize(cylinder.axisDirection);
  return rampVolume("cylinder", dims, ramp, [&](glm::dvec3 p) {
    const glm::dvec3 offset = p - cylinder.axisPoint;
    return cylinder.radiusVoxels - glm::length(offset - glm::dot(offset, axis) * axis);
  });
}

}  // namespace vsil::test
