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
// Built on the CPU from the volume's samples (read back from its texture). Rebuilt when the
// volume, the visible values, the radius or the halo mode change, kept otherwise; the CPU
// reference calls haloMaskVoxels and haloFieldVoxels.
//
// halo_mode=exact uses the mask as above (R8, one texture: its taps reach farther than a
// brick's overlap, so illustrate refuses it on a bricked volume). halo_mode=field (the
// default) replaces the mask by the halo field (haloFieldVoxels): RGBA8 per voxel, uploaded
// brick by brick in the volume texture's layout (slicing/gradient_texture.cpp's way): each
// voxel holds the result of its whole neighbourhood, so a sample reads only its own nearest
// voxel and a brick needs no more overlap than its samples do.
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "slicing/gl_objects.h"

namespace vsil {

class VolumeTexture;
struct SlabPart;

// How far, in voxels, the halo field at a voxel reads the volume beyond it (the mask's radius,
// the neighbours' reach and their gradients' central differences): a slab needs that much
// beyond its owned bricks' texels (the ghost width, slab.h techniqueGhostVoxels).
int haloFieldReachVoxels(double radius);

// 1 at the voxels within `radius` voxels (Euclidean, in voxel index space) of one that
// `visible` holds for, 0 elsewhere.
std::vector<std::uint8_t> haloMaskVoxels(const float* samples, glm::ivec3 dims,
                                         const std::function<bool(float)>& visible, double radius);

struct GradientTexels;

// The halo field (halo_mode=field): the view-independent half of the paper's halo, summed once
// per volume over a 3D neighbourhood instead of per sample over taps in the slice plane. At
// each voxel P that `mask` marks, over the 26 directions d_k of its 3x3x3 neighbours (unit in
// physical space; `spacing` turns voxel offsets into it) and the nearest voxel P_k at
// kHaloFieldReach·radius voxels along them:
//   F = (1/26)·Σ |∇f_k|·max(n_k·d_k, 0)^k_hpe,  N = Σ |∇f_k|·max(n_k·d_k, 0)^k_hpe·n_k / |…|,
// n_k the outward normal at P_k, d_k from P_k towards P. composite.frag then takes
// h = F·(1 − |N·V|)^k_hse·(1 − |∇f(P)|): the view term with the neighbourhood's mean normal
// instead of each neighbour's own (the paper gives no neighbourhood; ours decides: all 26
// directions at one reach, so halos surround a feature in 3D and need no per-view work).
// F below kHaloFieldFloor counts as 0: no halo there, so transparent samples there leave before
// shading (at k_ho = 1 such a halo adds under 0.7/255 opacity per sample; dropping it changed the
// bonsai's --effects halo --param k_hr=6,k_ho=2 picture on white by at most 4/255 and cut the
// engine's all-effects CPU-time ratio 2.33–2.37 → 1.97 in alternating runs).
// Bytes per voxel: RGB = 128 + round(127·N) (0 and ±1 exact); A = 0 where F = 0 and the 3x3x3
// neighbourhood's values are all transparent (`transparentRange`: the sample there is transparent
// whatever the trilinear weights, so composite.frag leaves before fetching the volume), 1 where F =
// 0 otherwise, else 1 + round(min(F·kHaloFieldScale, 1)·254) clamped to [4, 255].
inline constexpr double kHaloFieldReach = 0.75;
inline constexpr double kHaloFieldScale = 4.0;  // F rarely exceeds 1/4: 8 bits spent below it
inline constexpr float kHaloFieldFloor = float(2.5 / (254.0 * kHaloFieldScale));
std::vector<std::uint8_t> haloFieldVoxels(const GradientTexels& gradients,
                                          const std::vector<std::uint8_t>& mask,
                                          const float* samples,
                                          const std::function<bool(float, float)>& transparentRange,
                                          glm::dvec3 spacing, double radius, double pushExponent);
// F and N as composite.frag decodes them from the bytes.
float haloFieldStrength(std::uint8_t alpha);
glm::vec3 haloFieldNormal(const std::uint8_t* rgb);

enum class HaloMode { Field, Exact };

class HaloMaskTexture {
 public:
  // Rebuilds when `key` differs from the last build's (or the texture is missing): `key`
  // identifies the volume, the visible values, the radius, the mode and (field) k_hpe.
  // `transparentRange(lo, hi)`: no value in [lo, hi] is visible.
  void update(const std::vector<double>& key, const VolumeTexture& volume, glm::dvec3 spacing,
              HaloMode mode, const std::function<bool(float)>& visible,
              const std::function<bool(float, float)>& transparentRange, double radius,
              double pushExponent, const SlabPart* slab = nullptr);
  // The texture of brick `brick` of the volume's layout (exact: one texture, brick 0).
  GLuint id(std::size_t brick = 0) const { return textures_[brick].id(); }
  const std::vector<gl::TextureName>& brickTextures() const { return textures_; }
  // The bricks that read a voxel of the mask (empty_space.h bricksReading): with halo opacity,
  // these are occupied whatever the transfer function says of their values.
  const std::vector<bool>& bricks() const { return bricks_; }

 private:
  // A slab's field (slab.h): from its held voxels, exact at its owned bricks' texels.
  void updateSlab(const VolumeTexture& volume, glm::dvec3 spacing, const SlabPart& slab,
                  const std::function<bool(float)>& visible,
                  const std::function<bool(float, float)>& transparentRange, double radius,
                  double pushExponent);

  std::vector<double> key_;
  std::vector<bool> bricks_;
  std::vector<gl::TextureName> textures_;
};

}  // namespace vsil
