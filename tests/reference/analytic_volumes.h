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

// An infinite circular cylinder (cut by the volume's box) around the line through `axisPoint`
// along `axisDirection` (voxel coordinates): the same signed-distance ramp as ballsVolume,
// f = clamp01(0.5 + (radius - distance to the axis) / ramp), so f = 0.5 exactly on its surface.
// Seen from a direction perpendicular to the axis its silhouette is two straight lines.
struct Cylinder {
  glm::dvec3 axisPoint;
  glm::dvec3 axisDirection;
  double radiusVoxels;
};
Volume cylinderVolume(glm::ivec3 dims, const Cylinder& cylinder, double ramp = 8.0);

}  // namespace vsil::test
