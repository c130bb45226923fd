#pragma once
// Where feature halos may appear: an R8 3D texture over the volume's voxels, 1 within the halo
// radius k_hr (Euclidean, in voxels) of a visible voxel (one whose value the transfer function
// gives an opacity above 0), 0 elsewhere. A ball, not a box: halos reach as far in every
// direction, and the corners a box adds cost no samples (bonsai halo frame 2.47 -> 2.31 × the
// plain composite's CPU time). composite.frag applies halos only where the mask is 1, and lets
// transparent samples where it is 0 leave before any halo work: without it every transparent
// sample in the occupied bricks would pay the halo's taps (5–6× the plain composite's time on
// bonsai, as the earlier developer measured). Empty-space skipping counts the bricks that read
// a voxel of the mask as occupied (bricks()), so skipping still changes no pixel.
//
// Built on the CPU from the volume's samples (read back from its texture), one texture over
// the volume's voxels: halos read it by voxel index, so illustrate refuses halos on a volume of
// more than one brick (illustrate_technique.cpp). Rebuilt when the volume, the visible values
// or the radius change, kept otherwise; the CPU reference calls haloMaskVoxels.
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "slicing/gl_objects.h"

namespace vsil {

class VolumeTexture;

// 1 at the voxels within `radius` voxels (Euclidean, in voxel index space) of one that
// `visible` holds for, 0 elsewhere.
std::vector<std::uint8_t> haloMaskVoxels(const float* samples, glm::ivec3 dims,
                                         const std::function<bool(float)>& visible, double radius);

class HaloMaskTexture {
 public:
  // Rebuilds when `key` differs from the last build's (or the texture is missing): `key`
  // identifies the volume, the visible values and the radius.
  void update(const std::vector<double>& key, const VolumeTexture& volume,
              const std::function<bool(float)>& visible, double radius);
  GLuint id() const { return texture_.id(); }
  // The bricks that read a voxel of the mask (empty_space.h bricksReading): with halo opacity,
  // these are occupied whatever the transfer function says of their values.
  const std::vector<bool>& bricks() const { return bricks_; }

 private:
  std::vector<double> key_;
  std::vector<bool> bricks_;
  gl::TextureName texture_;
};

}  // namespace vsil
