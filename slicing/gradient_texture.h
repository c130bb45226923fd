#pragma once
// Per-voxel gradients of the volume, computed once per volume and sampled by every frame of the
// techniques that shade or enhance by the gradient (illustrate; mip's and semantic's lighting
// next). One RGBA16F 3D texture, trilinear, clamped: (n.x, n.y, n.z, m) per voxel with
//   g = central differences in voxel index space divided by the spacing (the gradient in the
//       data's physical units; samples beyond the border clamp to it, as the volume texture's
//       sampling does, so border voxels take one-sided halves),
//   n = g / |g| (0 where g = 0): the direction, in physical axes (world space up to a uniform
//       scale, so eyeFromWorld's rotation turns it into eye space),
//   m = |g| / max |g| over the volume (0 everywhere for a constant volume).
// Half floats hold unit components to 2^-11 and filter in float on llvmpipe like the volume's
// R16F, so the CPU reference (tests/reference) reads the very texels the GL path samples.
//
// Built on the CPU from the volume texture's own samples (read back once), on every hardware
// thread, and uploaded brick by brick in the volume texture's layout (the same overlap and
// padding, so a piece of a slice reads its brick's gradients as it reads its samples): the earlier
// developer measured it faster than a GL pass on llvmpipe (not re-measured since), and the
// reference calls the same function.
#include <cstdint>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "slicing/gl_objects.h"

namespace vsil {

struct GradientTexels {
  glm::ivec3 dims{0};
  std::vector<std::uint16_t> halves;  // RGBA per voxel, x fastest (glm::packHalf1x16)
  float maxMagnitude = 0;             // max |g| before normalization

  glm::vec4 at(int x, int y, int z) const;  // unpacked
};

// max |g| over the volume; `samples`: dims.x·dims.y·dims.z floats, x fastest.
float maxGradientMagnitude(const float* samples, glm::ivec3 dims, glm::dvec3 spacing);
// The texels of the slices z in [zBegin, zEnd) (texels.dims.z = zEnd − zBegin), normalized by
// `maxMagnitude`.
GradientTexels computeGradientTexels(const float* samples, glm::ivec3 dims, glm::dvec3 spacing,
                                     float maxMagnitude, int zBegin, int zEnd);
// Every slice.
GradientTexels computeGradientTexels(const float* samples, glm::ivec3 dims, glm::dvec3 spacing);

class VolumeTexture;

// One RGBA16F texture per brick of the volume texture, with its layout (core/brick_layout.h).
class GradientTexture {
 public:
  // Reads the volume texture back and uploads the gradients of its samples.
  GradientTexture(const VolumeTexture& volume, glm::dvec3 spacing);
  GLuint brickTexture(std::size_t brick) const { return textures_[brick].id(); }
  double buildMs() const { return buildMs_; }

 private:
  std::vector<gl::TextureName> textures_;
  double buildMs_ = 0;
};

// The Renderer's gradient texture: built on first use in a frame, kept until the volume
// changes (reset).
class GradientTextureCache {
 public:
  void reset(const VolumeTexture* volume, glm::dvec3 spacing);
  // The texture (building it now if no frame asked before).
  const GradientTexture& texture();
  bool built() const { return texture_.has_value(); }

 private:
  const VolumeTexture* volume_ = nullptr;
  glm::dvec3 spacing_{1.0};
  std::optional<GradientTexture> texture_;
};

}  // namespace vsil
