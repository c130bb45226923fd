#include "analytic_volumes.h"

#include <algorithm>
#include <cmath>

namespace vsil::test {

Volume ballsVolume(glm::ivec3 dims, const std::vector<Ball>& balls, double ramp) {
  Volume volume;
  volume.name = "balls";
  volume.source = "test:balls";
  volume.dims = dims;
  volume.type = SampleType::Float32;
  volume.samples.resize(volume.voxelCount());
  for (int z = 0; z < dims.z; ++z) {
    for (int y = 0; y < dims.y; ++y) {
      for (int x = 0; x < dims.x; ++x) {
        double f = 0.0;
        for (const Ball& ball : balls) {
          const double r = glm::length(glm::dvec3(x, y, z) - ball.centreVoxel);
          f = std::max(f, std::clamp(0.5 + (ball.radiusVoxels - r) / ramp, 0.0, 1.0));
        }
        volume.samples[volume.index(x, y, z)] = float(f);
      }
    }
  }
  return volume;
}

Volume cylinderVolume(glm::ivec3 dims, const Cylinder& cylinder, double ramp) {
  Volume volume;
  volume.name = "cylinder";
  volume.source = "test:cylinder";
  volume.dims = dims;
  volume.type = SampleType::Float32;
  volume.samples.resize(volume.voxelCount());
  const glm::dvec3 axis = glm::normalize(cylinder.axisDirection);
  for (int z = 0; z < dims.z; ++z) {
    for (int y = 0; y < dims.y; ++y) {
      for (int x = 0; x < dims.x; ++x) {
        const glm::dvec3 offset = glm::dvec3(x, y, z) - cylinder.axisPoint;
        const double r = glm::length(offset - glm::dot(offset, axis) * axis);
        volume.samples[volume.index(x, y, z)] =
            float(std::clamp(0.5 + (cylinder.radiusVoxels - r) / ramp, 0.0, 1.0));
      }
    }
  }
  return volume;
}

}  // namespace vsil::test
