#pragma once
// The CPU twin of slicing/shaders/common.glsl: the same sample positions (pixel centres on the
// view-aligned slice planes of slicing/slicer.h), computed in float with the same operations,
// and trilinear interpolation as OpenGL defines it for a clamped float 3D texture.
#include <array>
#include <vector>

#include <glm/glm.hpp>

#include "core/camera.h"
#include "core/volume.h"
#include "slicing/gradient_texture.h"
#include "slicing/slicer.h"

namespace vsil::reference {

// GL's linear filtering of a clamped texture along one axis: texel space u·n − 0.5.
struct LinearTaps {
  int i0, i1;
  float f;
};
LinearTaps linearTaps(float u, int n);

// A 1D RGBA texture (a transfer function's table, slicing/transfer_function_texture.h) read with
// linear filtering at texture coordinate `u`.
glm::vec4 sampleTable(const std::vector<glm::vec4>& table, float u);

// The texels of the volume texture (slicing/volume_texture.h): every sample as a float in the
// data's own units, x fastest. What the GL path reads back to build gradients and halo masks.
std::vector<float> textureTexels(const Volume& volume);

// The gradient texture sampled trilinearly at the (quantized) voxel position `voxel` (what
// texture() returns from the RGBA16F texels, clamped at the edges).
glm::vec4 sampleGradientTexels(const GradientTexels& texels, glm::vec3 voxel);

// A gradient texel or an interpolation of them, (g/M, ·), split as shaders/gradients.glsl
// splitGradient splits it.
struct SplitGradient {
  glm::vec3 direction{0.0f};  // g/|g|, 0 where g vanishes
  float magnitude = 0;        // min(|g/M|, 1)
  bool hasDirection = false;  // g ≠ 0
};
SplitGradient splitGradient(glm::vec4 texel);

// A voxel position rounded as the shaders round it (common.glsl quantizedVoxel).
glm::vec3 quantizedVoxel(glm::vec3 voxel);

// Up to eight voxel positions (two per axis), the first the one sliceVoxel computes.
struct VoxelCandidates {
  std::array<glm::vec3, 8> positions;
  int count = 0;
};

class SliceSampler {
 public:
  SliceSampler(const Volume& volume, const View& view);

  // The eye-space point of pixel (x, y) (top-left origin) on the plane at `eyeDistance`.
  glm::vec3 eyePoint(int x, int y, float eyeDistance) const;
  glm::vec3 voxelFromEyePoint(glm::vec3 eye) const;
  // Trilinear, clamp to edge, at a quantized voxel position: the texel-space coordinate the
  // sampler computes from a brick's texture coordinate is then the position itself (its
  // floor and fraction are the taps and weights; common.glsl brickTexCoord).
  float sample(glm::vec3 voxel) const;

  // What the slice passes sample (common.glsl sliceVoxel): the voxel position of pixel (x, y)
  // on a slice, and whether it lies in the volume's box.
  glm::vec3 sliceVoxel(int x, int y, const SliceVoxelCoords& slice) const;
  // sliceVoxel first, then the other positions the shader may round to: its float rounding
  // before quantizedVoxel may differ from this computation's by a few units in the last place
  // (a fused multiply-add, another order), which tips the rounding to 1/1024 voxel the other
  // way where the unrounded position lies that close to a boundary between two steps.
  VoxelCandidates sliceVoxelCandidates(int x, int y, const SliceVoxelCoords& slice) const;
  // The same for the MIP family's sampling (common.glsl RAY_SAMPLING: pixelRay, rayVoxel): slice
  // k's sample on pixel (x, y)'s ray, first the one computed here.
  VoxelCandidates rayVoxelCandidates(int x, int y, const PixelRays& rays, int k) const;
  // The compositing techniques' samples (common.glsl BOX_ALIGNED_SAMPLING): pixel (x, y)'s ray
  // (as rayVoxelCandidates) and its phase; slice k samples boxAlignedVoxel(ray, k).
  struct BoxAlignedRay {
    glm::vec3 origin{0.0f}, direction{0.0f};
    float stepEye = 0, phase = 0;
    // The phase within rounding of 0 or 1: GL may have taken the other, which moves every
    // sample one slice (the same positions, the planes' depths one step apart).
    bool phaseAmbiguous = false;
  };
  BoxAlignedRay boxAlignedRay(int x, int y, const PixelRays& rays) const;
  static glm::vec3 boxAlignedVoxel(const BoxAlignedRay& ray, int k);
  bool insideVolume(glm::vec3 voxel) const;
  glm::vec3 gradientVoxel(glm::vec3 voxel) const;
  // −∇f/|∇f| in eye space, 0 where the gradient vanishes (common.glsl outwardNormalEye).
  glm::vec3 outwardNormalEye(glm::vec3 voxel) const;
  float facingRatio(glm::vec3 voxel, glm::vec3 eye) const;  // |n·v| as in common.glsl

 private:
  glm::vec2 fragCoord(int x, int y) const;    // gl_FragCoord.xy of pixel (x, y), exact
  glm::vec2 fragmentNdc(int x, int y) const;  // gl_FragCoord's NDC as common.glsl computes it
  // The positions a sum of float terms may round to: `unrounded` as computed here, `magnitude`
  // per axis the sum of its terms' magnitudes (the scale of their rounding).
  static VoxelCandidates candidatesNear(glm::vec3 unrounded, glm::vec3 magnitude);

  const Volume& volume_;
  const View& view_;
  glm::mat4 voxelFromEye_;
  glm::mat3 eyeFromVoxelGradient_;
  glm::vec2 viewportSize_;
  glm::vec2 halfExtent_;
  glm::vec3 dims_;
};

}  // namespace vsil::reference
