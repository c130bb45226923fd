#include "slicing/volume_texture.h"

#include <cmath>

#include "core/error.h"

namespace vsil {

namespace {

// Half floats hold every integer up to 2048 exactly; sampling R16F costs llvmpipe about a
// quarter less than R32F (bonsai, 512², single thread: 620 -> 450 ms per OPS frame) and
// filters the same values in float, so the result is unchanged.
bool exactInHalfFloat(const std::vector<float>& samples) {
  for (float v : samples) {
    if (v != std::nearbyint(v) || std::abs(v) > 2048.0f) return false;
  }
  return true;
}

}  // namespace

VolumeTexture::VolumeTexture(const Volume& volume)
    : dims_(volume.dims), internalFormat_(exactInHalfFloat(volume.samples) ? GL_R16F : GL_R32F) {
  GLint maxSize = 0;
  glGetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &maxSize);
  for (int axis = 0; axis < 3; ++axis) {
    if (dims_[axis] > maxSize) {
      throwInputError(volume.source, "dimension " + std::to_string(dims_[axis]) +
                                         " exceeds the OpenGL 3D texture limit of " +
                                         std::to_string(maxSize));
    }
  }
  if (volume.samples.size() != volume.voxelCount()) {
    throw std::logic_error("VolumeTexture: sample count does not match the dimensions");
  }
  texture_ = gl::createTexture();
  VSIL_GL(glBindTexture(GL_TEXTURE_3D, texture_.id()));
  VSIL_GL(glPixelStorei(GL_UNPACK_ALIGNMENT, 1));
  VSIL_GL(glTexImage3D(GL_TEXTURE_3D, 0, GLint(internalFormat_), dims_.x, dims_.y, dims_.z, 0,
                       GL_RED, GL_FLOAT, volume.samples.data()));
  glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  for (GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R}) {
    glTexParameteri(GL_TEXTURE_3D, wrap, GL_CLAMP_TO_EDGE);
  }
  VSIL_GL(glBindTexture(GL_TEXTURE_3D, 0));
}

}  // namespace vsil
