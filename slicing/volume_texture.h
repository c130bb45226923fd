#pragma once
// The volume as a 3D texture in the data's own units, trilinear filtering, clamped at the
// edges: R16F where every sample is an integer of magnitude <= 2048 (8-bit data, most CT),
// else R32F. Either holds the samples exactly. The voxel aspect lives in the View, not here.
//
// The samples stay in the volume's own type; the upload converts each brick slab by slab of z
// (convertTexels), on a second thread while the previous slab is uploaded, so no float copy of
// the whole volume ever exists.
#include <cstddef>
#include <span>
#include <vector>

#include "core/brick_layout.h"
#include "core/volume.h"
#include "slicing/gl_objects.h"
#include "slicing/slab.h"

namespace vsil {

// GL_R16F when every sample of `volume` is an integer of magnitude <= 2048 (always for 8-bit
// types; for 16-bit types by the value range; for floats by a scan), else GL_R32F.
GLenum textureFormatFor(const Volume& volume);
// Bytes per texel of GL_R16F (2) or GL_R32F (4).
std::size_t texelSize(GLenum internalFormat);
// Whether the current context can create a 3D texture of `dims` in `internalFormat`
// (GL_PROXY_TEXTURE_3D: llvmpipe refuses textures beyond about 1.75 GiB, limits.h).
bool textureFits(glm::ivec3 dims, GLenum internalFormat);

// Whether a volume of `dims` fits one texture of `internalFormat` (padded to powers of two)
// within `maxTextureBytes` and what the context can create.
bool fitsOneTexture(glm::ivec3 dims, GLenum internalFormat, std::uint64_t maxTextureBytes);

// The samples of the box [origin, origin + size) (x fastest, then y, then z) as texels of
// `internalFormat`, into `out` (size.x·size.y·size.z·texelSize bytes): half-float bits for
// GL_R16F (exact: the caller chose it by textureFormatFor), floats for GL_R32F. The box may
// reach past the volume's far sides (a brick's power-of-two padding): those texels repeat the
// last voxel, as CLAMP_TO_EDGE would read it.
void convertTexels(const Volume& volume, glm::ivec3 origin, glm::ivec3 size, GLenum internalFormat,
                   std::span<std::byte> out);

// The volume as bricked 3D textures (core/brick_layout.h BrickLayout::choose): one brick when
// the whole volume, padded to powers of two, fits one texture within `maxTextureBytes` and
// wastes little to padding (or whenever it fits, with Bricking::OneIfItFits); else the fewest
// bricks that stay close to the voxels. Throws InputError naming the volume's source when no
// brick fits (textureFits), before allocating any.
class VolumeTexture {
 public:
  // `slabBytes`: about how many bytes of texels each converted slab holds (tests make it small
  // to cross many slab borders).
  explicit VolumeTexture(const Volume& volume,
                         std::uint64_t maxTextureBytes = limits::kMaxTextureBytes,
                         std::size_t slabBytes = limits::kUploadSlabBytes,
                         BrickLayout::Bricking bricking = BrickLayout::Bricking::Compact);
  // One process's part of a volume split into slabs (slicing/slab.h): the whole volume's layout,
  // textures only for the bricks `slab` holds (0 for the others), from `slabVolume`, which holds
  // the whole volume's z from slab.voxelZ0 on.
  VolumeTexture(const Volume& slabVolume, const SlabPart& slab,
                std::size_t slabBytes = limits::kUploadSlabBytes);
  const BrickLayout& layout() const { return layout_; }
  std::size_t brickCount() const { return textures_.size(); }
  GLuint brickTexture(std::size_t brick) const { return textures_[brick].id(); }
  glm::ivec3 dims() const { return dims_; }
  GLenum internalFormat() const { return internalFormat_; }
  // Every voxel as a float, x fastest (the texels read back from the bricks: what gradients and
  // halo masks are built from).
  std::vector<float> readVoxels() const;
  // The voxels of z in [zBegin, zEnd) (dims.x·dims.y·(zEnd − zBegin) floats), from the bricks
  // this texture holds: a slab's (slab.h), which must hold every brick owning those voxels.
  std::vector<float> readVoxels(int zBegin, int zEnd) const;

 private:
  // Uploads the layout's bricks from `volume`, whose z = 0 is the whole volume's `zShift`;
  // with `slab`, only those it holds.
  void upload(const Volume& volume, std::size_t slabBytes, int zShift, const SlabPart* part);
  BrickLayout layout_;
  std::vector<gl::TextureName> textures_;  // one per brick, in the layout's order
  glm::ivec3 dims_;
  GLenum internalFormat_;
};

// Uploads `texels` (RGBA16F halves, or R8 bytes, per voxel of the volume of `dims`, x fastest)
// as one texture per brick of `layout`, with the bricks' overlap and padding (what the volume
// texture holds at each texel, for these per-voxel values). For gradient and halo textures.
std::vector<gl::TextureName> uploadBricked(const BrickLayout& layout, glm::ivec3 dims,
                                           GLenum internalFormat, GLenum format, GLenum type,
                                           std::size_t bytesPerVoxel, const void* texels);
// A slab's (slab.h): only the bricks `slab` holds (0 for the others), from `texels` of the
// voxels z in [zFirst, zFirst + zCount) of the volume; texels of held bricks beyond them repeat
// the nearest (no owned piece samples them: the caller checks).
std::vector<gl::TextureName> uploadBricked(const BrickLayout& layout, glm::ivec3 dims,
                                           GLenum internalFormat, GLenum format, GLenum type,
                                           std::size_t bytesPerVoxel, const void* texels,
                                           const SlabPart& slab, int zFirst, int zCount);

}  // namespace vsil
