#pragma once
// How a volume is cut into bricks that each fit one 3D texture (slicing/volume_texture.h).
// Pure arithmetic on the dimensions, no GL: the memory check before reading
// (limits::renderVolumeBytes) and the upload use the same layout.
//
// Along each axis, bricks of texture sizes S_i, powers of two: brick i owns the sample positions
// [b_i − 0.5, b_{i+1} − 0.5] with b_0 = 0 and b_{i+1} = b_i + S_i − 4 (the first from −∞, the
// last to +∞; the slice polygons are cut on these planes) and stores the voxels
// [origin, origin + S_i) with origin = max(0, b_i − 2): two voxels of overlap on each side,
// enough for the trilinear taps of a sample and of its central-difference neighbours one voxel
// away. Voxels past the volume's end are stored as copies of the last one (what CLAMP_TO_EDGE
// would read). A texture's size is a power of two along every axis so that a sample's
// brick-local texture coordinate (voxel − origin + 0.5) / size times size is exact, and the
// sampler filters the same texels with the same weights in every brick (common.glsl).
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

namespace vsil {

struct Brick {
  glm::ivec3 index{0};   // position in the grid of bricks
  glm::ivec3 origin{0};  // the volume voxel stored in texel 0
  glm::ivec3 size{0};    // the texture's size, powers of two
  // The sample positions this brick owns, in voxel coordinates; ±1e30 at the volume's sides.
  glm::dvec3 low{0.0};
  glm::dvec3 high{0.0};
};

class BrickLayout {
 public:
  // Overlap stored on each side of a brick's own voxels.
  static constexpr int kOverlap = 2;
  // The smallest brick texture side: the first power of two above 2·kOverlap.
  static constexpr int kMinStorage = 8;
  // Where sample positions are rounded to (1/1024 voxel, common.glsl quantizedVoxel): every
  // brick-local coordinate is then exact in float for volumes up to 8192 voxels per side.
  static constexpr float kSampleQuantum = 1.0f / 1024.0f;

  // Total texels a layout may take, relative to the voxels and overlap copies it stores.
  static constexpr double kMaxWaste = 1.3;
  // Axes shorter than this count as this long in that bound: the smallest brick (8 texels,
  // 4 voxels of its own) cannot hold them in fewer texels than the next power of two.
  static constexpr int kSmallestCutSide = 32;
  // The padding one texture may carry (bytes beyond the voxels'), as a share of the texture
  // limit (904 MiB of the default 1808): several bricks cost up to twice the frame time on
  // llvmpipe (silhouette at 512² of a 300³ volume: 349 ms in one texture padded to 512³, 711 ms
  // in 8 bricks of 256 + 64 texels per axis), padding only memory, which --max-memory counts.
  static constexpr double kPaddingShareOfLimit = 0.5;

  // One brick (each axis padded to a power of two) when that texture fits in
  // `maxTextureBytes` and `maxTextureSide` and its padding is within kMaxWaste of the voxels or
  // at most kPaddingShareOfLimit of `maxTextureBytes` (or, with Bricking::OneIfItFits, whenever it
  // fits: for what cannot follow bricks, the tiles march); else, among the layouts whose bricks
  // each fit, the fewest bricks whose texels are within kMaxWaste of the voxels and overlap they
  // store (storedTexels; each brick costs a draw per slice piece), then the fewest texels. Along an
  // axis the bricks are one power of two, then smaller ones at the end: 300 voxels take 256 + 64
  // texels, 400 take 256 + 128 + 32. Throws std::invalid_argument when not even 8³ texels fit.
  enum class Bricking { Compact, OneIfItFits };
  static BrickLayout choose(glm::ivec3 dims, std::size_t texelBytes, std::uint64_t maxTextureBytes,
                            int maxTextureSide, Bricking bricking = Bricking::Compact);
  // The voxels and overlap copies the layout stores, each axis counted as at least
  // kSmallestCutSide: what kMaxWaste is a bound on.
  double storedTexels() const;
  // The layout with texture size `storage` (powers of two, each > 2·kOverlap) along each axis.
  static BrickLayout withStorage(glm::ivec3 dims, glm::ivec3 storage);
  BrickLayout() = default;
  BrickLayout(glm::ivec3 dims, glm::ivec3 counts, std::vector<Brick> bricks)
      : dims_(dims), counts_(counts), bricks_(std::move(bricks)) {}

  glm::ivec3 dims() const { return dims_; }
  glm::ivec3 counts() const { return counts_; }
  const std::vector<Brick>& bricks() const { return bricks_; }
  std::size_t size() const { return bricks_.size(); }
  // Texels of all bricks' textures together.
  std::uint64_t texels() const;
  // The largest brick texture in texels.
  std::uint64_t largestTexels() const;

 private:
  glm::ivec3 dims_{0};
  glm::ivec3 counts_{0};
  std::vector<Brick> bricks_;  // x fastest
};

// The smallest power of two >= n (n >= 1).
int nextPowerOfTwo(int n);

}  // namespace vsil
