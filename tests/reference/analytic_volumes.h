#pragma once
// Volumes made in tests, whose iso-surfaces are known exactly.
#include <vector>

#include "core/volume.h"

namespace vsil::test {

struct Ball {
  glm::dvec3 centreVoxel;
  double radiusVoxels;  // radius of the iso-surface f = 0.5
};

// f = max over balls of clamp01(0.5 + (radius - |p - centre|) / ramp): a signed-distance ramp,
// so f = 0.5 exactly on each sphere and the union's surface is the union of the spheres.
Volume ballsVolume(glm::ivec3 dims, const std::vector<Ball>& balls, double ramp = 8.0);

}  // namespace vsil::test
