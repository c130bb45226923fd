#pragma once
// The volume as a 3D texture in the data's own units, trilinear filtering, clamped at the
// edges: R16F where every sample is an integer of magnitude <= 2048 (8-bit data, most CT),
// else R32F. Either holds the samples exactly. The voxel aspect lives in the View, not here.
//
// The samples stay in the volume's own type; the upload converts them slab by slab of z
// (convertTexels), on a second thread while the previous slab is uploaded, so no float copy of
// the whole volume ever exists. convertTexels converts any box, so a brick of a bricked
// texture can be converted and uploaded on its own.
#include <cstddef>
#include <span>

#include "core/volume.h"
#include "slicing/gl_objects.h"

namespace vsil {

// GL_R16F when every sample of `volume` is an integer of magnitude <= 2048 (always for 8-bit
// types; for 16-bit types by the value range; for floats by a scan), else GL_R32F.
GLenum textureFormatFor(const Volume& volume);
// Bytes per texel of GL_R16F (2) or GL_R32F (4).
std::size_t texelSize(GLenum internalFormat);
// Whether the current context can create a 3D texture of `dims` in `internalFormat`
// (GL_PROXY_TEXTURE_3D: llvmpipe refuses textures beyond about 1.75 GiB, limits.h).
bool textureFits(glm::ivec3 dims, GLenum internalFormat);

// The samples of the box [origin, origin + size) (x fastest, then y, then z) as texels of
// `internalFormat`, into `out` (size.x·size.y·size.z·texelSize bytes): half-float bits for
// GL_R16F (exact: the caller chose it by textureFormatFor), floats for GL_R32F.
void convertTexels(const Volume& volume, glm::ivec3 origin, glm::ivec3 size, GLenum internalFormat,
                   std::span<std::byte> out);

// Throws InputError naming the volume's source when a dimension exceeds
// GL_MAX_3D_TEXTURE_SIZE or the texture does not fit (textureFits), before allocating it.
class VolumeTexture {
 public:
  // `slabBytes`: about how many bytes of texels each converted slab holds (tests make it small
  // to cross many slab borders).
  explicit VolumeTexture(const Volume& volume, std::size_t slabBytes = limits::kUploadSlabBytes);
  GLuint id() const { return texture_.id(); }
  glm::ivec3 dims() const { return dims_; }
  GLenum internalFormat() const { return internalFormat_; }

 private:
  gl::TextureName texture_;
  glm::ivec3 dims_;
  GLenum internalFormat_;
};

}  // namespace vsil
