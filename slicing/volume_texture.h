#pragma once
// The volume as a 3D texture: R32F in the data's own units (exact for every sample type),
// trilinear filtering, clamped at the edges. The voxel aspect lives in the View, not here.
#include "core/volume.h"
#include "slicing/gl_objects.h"

namespace vsil {

class VolumeTexture {
 public:
  explicit VolumeTexture(const Volume& volume);
  GLuint id() const { return texture_.id(); }
  glm::ivec3 dims() const { return dims_; }

 private:
  gl::TextureName texture_;
  glm::ivec3 dims_;
};

}  // namespace vsil
