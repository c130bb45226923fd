#pragma once
// The CPU twin of slicing/shaders/common.glsl: the same sample positions (pixel centres on the
// view-aligned slice planes of slicing/slicer.h), computed in float with the same operations,
// and trilinear interpolation as OpenGL defines it for a clamped float 3D texture.
#include <glm/glm.hpp>

#include "core/camera.h"
#include "core/volume.h"

namespace vsil::reference {

class SliceSampler {
 public:
  SliceSampler(const Volume& volume, const View& view);

  // The eye-space point of pixel (x, y) (top-left origin) on the plane at `eyeDistance`.
  glm::vec3 eyePoint(int x, int y, float eyeDistance) const;
  glm::vec3 voxelFromEyePoint(glm::vec3 eye) const;
  bool insideVolume(glm::vec3 voxel) const;
  float sample(glm::vec3 voxel) const;  // trilinear, clamp to edge
  glm::vec3 gradientVoxel(glm::vec3 voxel) const;
  float facingRatio(glm::vec3 voxel, glm::vec3 eye) const;  // |n·v| as in common.glsl

 private:
  const Volume& volume_;
  const View& view_;
  glm::mat4 voxelFromEye_;
  glm::mat3 eyeFromVoxelGradient_;
  glm::vec2 viewportSize_;
  glm::vec2 halfExtent_;
  glm::vec3 dims_;
};

}  // namespace vsil::reference
