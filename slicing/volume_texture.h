#pragma once
// The volume as a 3D texture in the data's own units, trilinear filtering, clamped at the
// edges: R16F where every sample is an integer of magnitude <= 2048 (8-bit data, most CT),
// else R32F. Either holds the samples exactly. The voxel aspect lives in the View, not here.
#include "core/volume.h"
#include "slicing/gl_objects.h"

namespace vsil {

class VolumeTexture {
 public:
  explicit VolumeTexture(const Volume& volume);
  GLuint id() const { return texture_.id(); }
  glm::ivec3 dims() const { return dims_; }
  GLenum internalFormat() const { return internalFormat_; }

 private:
  gl::TextureName texture_;
  glm::ivec3 dims_;
  GLenum internalFormat_;
};

}  // namespace vsil
