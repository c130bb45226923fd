#pragma once
// Per-voxel gradients of the volume, computed once per volume and sampled by every frame of the
// techniques that shade or enhance by the gradient (illustrate, semantic; shaders/gradients.glsl
// reads them). One RGBA16F 3D texture, trilinear, clamped: (g/M, value) per voxel with
//   g = central differences in voxel index space divided by the spacing (the gradient in the
//       data's physical units; samples beyond the border clamp to it, as the volume texture's
//       sampling does, so border voxels take one-sided halves), in physical axes (world space
//       up to a uniform scale, so eyeFromWorld's rotation turns it into eye space),
//   M = max |g| over the volume, so that |g/M| in [0, 1] is the normalized magnitude and
//       g/|g| the direction (shaders split the interpolated g/M into both; a constant volume
//       has g = 0 everywhere),
//   value = the voxel's value where the volume texture is R16F (its texels are then exact in half
//       floats, volume_texture.h), else 0: a sample then gets its value and its gradient from
//       one fetch (the shaders' GRADIENTS_HOLD_VALUES, GradientTexture::addDefines).
// Storing g/M rather than a unit direction and |g|/M keeps the same information in the same four
// channels (half floats keep 11 bits relative down to 2^-14·M) and frees the fourth for the
// value. It also means the direction and magnitude between voxels are those of the interpolated
// gradient, as when differencing the interpolated field, not interpolated unit vectors.
// Half floats filter in float on llvmpipe like the volume's R16F, so the CPU reference
// (tests/reference) reads the very texels the GL path samples.
//
// Built on the CPU from the volume texture's own samples (read back once), on every hardware
// thread, and uploaded brick by brick in the volume texture's layout (the same overlap and
// padding, so a piece of a slice reads its brick's gradients as it reads its samples): the earlier
// developer measured it faster than a GL pass on llvmpipe (not re-measured since), and the
// reference calls the same function.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "slicing/gl_objects.h"

namespace vsil {

struct GradientTexels {
  glm::ivec3 dims{0};
  std::vector<std::uint16_t> halves;  // RGBA per voxel, x fastest (glm::packHalf1x16)
  float maxMagnitude = 0;             // M = max |g|
  bool holdsValues = false;           // alpha: the voxel's value (else 0)

  glm::vec4 at(int x, int y, int z) const;  // unpacked
};

// max |g| over the volume; `samples`: dims.x·dims.y·dims.z floats, x fastest.
float maxGradientMagnitude(const float* samples, glm::ivec3 dims, glm::dvec3 spacing);
// max |g|² over the voxels z in [zBegin, zEnd).
float maxSquaredGradient(const float* samples, glm::ivec3 dims, glm::dvec3 spacing, int zBegin,
                         int zEnd);
// The texels of the slices z in [zBegin, zEnd) (texels.dims.z = zEnd − zBegin), gradients
// divided by `maxMagnitude`, with the samples in alpha when `withValues`.
GradientTexels computeGradientTexels(const float* samples, glm::ivec3 dims, glm::dvec3 spacing,
                                     float maxMagnitude, int zBegin, int zEnd, bool withValues);
// Every slice.
GradientTexels computeGradientTexels(const float* samples, glm::ivec3 dims, glm::dvec3 spacing,
                                     bool withValues);
// Whether the volume texture's texels are exact in half floats, so gradient texels hold them.
bool gradientsCanHoldValues(GLenum volumeInternalFormat);

class VolumeTexture;
struct SlabPart;

// The ghost width (TechniqueInfo::slabGhostVoxels) a slab's gradients need: the central
// differences at every texel of an owned brick (its apron voxel, then the neighbour), two
// voxels (the slab constructor below checks).
inline constexpr int kGradientGhostVoxels = 2;

// One RGBA16F texture per brick of the volume texture, with its layout (core/brick_layout.h).
class GradientTexture {
 public:
  // Reads the volume texture back and uploads the gradients of its samples.
  GradientTexture(const VolumeTexture& volume, glm::dvec3 spacing);
  // A slab's (slab.h): the gradients of the bricks it holds, from its held voxels, the whole
  // volume's at every texel of its owned bricks (the ghost layers give the central differences
  // their neighbours), divided by the whole volume's M agreed over the processes.
  GradientTexture(const VolumeTexture& volume, glm::dvec3 spacing, const SlabPart& slab);
  GLuint brickTexture(std::size_t brick) const { return textures_[brick].id(); }
  double buildMs() const { return buildMs_; }
  // shaders/gradients.glsl's define for this texture, added to `defines` where it applies.
  void addDefines(std::vector<std::string>& defines) const;

 private:
  std::vector<gl::TextureName> textures_;
  double buildMs_ = 0;
  bool holdsValues_ = false;
};

// The Renderer's gradient texture: built on first use in a frame, kept until the volume
// changes (reset).
class GradientTextureCache {
 public:
  void reset(const VolumeTexture* volume, glm::dvec3 spacing, const SlabPart* slab = nullptr);
  // The texture (building it now if no frame asked before).
  const GradientTexture& texture();
  bool built() const { return texture_.has_value(); }

 private:
  const VolumeTexture* volume_ = nullptr;
  glm::dvec3 spacing_{1.0};
  const SlabPart* slab_ = nullptr;
  std::optional<GradientTexture> texture_;
};

}  // namespace vsil
