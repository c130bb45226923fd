#pragma once
// The uniforms every pass reads (shaders/common.glsl), in two std140 uniform blocks: the
// frame's (camera, volume) uploaded once per frame, and one block per slice (where its pixels
// sample the volume, its depths), all uploaded once per frame into one buffer; a pass binds its
// slice's block with one glBindBufferRange instead of about fifteen glUniform calls per program.
// Compute shaders that walk the slices themselves (tile_march.h) read a range of consecutive
// slices' blocks as one uniform block of vec4s (shaders/tile_march.glsl sliceAt).
#include <cstddef>
#include <cstdint>

#include <glm/glm.hpp>

#include "core/brick_layout.h"
#include "core/camera.h"
#include "slicing/gl_objects.h"
#include "slicing/slicer.h"

namespace vsil {

// Mirrors `uniform FrameBlock` in shaders/common.glsl (std140 offsets checked below).
struct FrameBlock {
  glm::mat4 voxelFromEye;
  glm::mat4 clipFromVoxel;
  glm::vec4 eyeFromVoxelGradient[3];  // mat3 columns, each padded to a vec4 (std140)
  glm::vec3 volumeDims;
  std::int32_t orthographic;
  glm::vec2 viewportSize;
  glm::vec2 halfExtent;
  // slicer.h PixelRays, each vec3 padded to a vec4 but for the step beside the first
  glm::vec3 rayOriginPerWindowX;
  float rayStepEye;
  glm::vec4 rayOriginPerWindowY;
  glm::vec4 rayOriginAtWindowOrigin;
  glm::vec4 rayDirectionPerWindowX;
  glm::vec4 rayDirectionPerWindowY;
  glm::vec3 rayDirectionAtWindowOrigin;
};
static_assert(offsetof(FrameBlock, eyeFromVoxelGradient) == 128);
static_assert(offsetof(FrameBlock, volumeDims) == 176);
static_assert(offsetof(FrameBlock, orthographic) == 188);
static_assert(offsetof(FrameBlock, viewportSize) == 192);
static_assert(offsetof(FrameBlock, halfExtent) == 200);
static_assert(offsetof(FrameBlock, rayOriginPerWindowX) == 208);
static_assert(offsetof(FrameBlock, rayStepEye) == 220);
static_assert(offsetof(FrameBlock, rayDirectionAtWindowOrigin) == 288);

// Mirrors `uniform SliceBlock` in shaders/common.glsl.
struct SliceBlock {
  glm::vec3 voxelPerNdcX;  // slicer.h SliceVoxelCoords
  float eyeDistance;       // -z_eye of the plane
  glm::vec3 voxelPerNdcY;
  float depth;  // normalized depth d of the plane
  glm::vec3 voxelAtNdcOrigin;
  float windowDepth;    // what the depth test compares
  float previousDepth;  // the previous slice's d (0 before the first)
  std::uint32_t index;  // the slice's index in the plan
};
// The vec4 words tile_march.glsl's sliceAt() reads: (voxelPerNdcX, eyeDistance), (voxelPerNdcY,
// depth), (voxelAtNdcOrigin, windowDepth), (previousDepth, index, -, -).
static_assert(offsetof(SliceBlock, eyeDistance) == 12);
static_assert(offsetof(SliceBlock, voxelPerNdcY) == 16);
static_assert(offsetof(SliceBlock, depth) == 28);
static_assert(offsetof(SliceBlock, voxelAtNdcOrigin) == 32);
static_assert(offsetof(SliceBlock, windowDepth) == 44);
static_assert(offsetof(SliceBlock, previousDepth) == 48);
static_assert(offsetof(SliceBlock, index) == 52);

// Mirrors `uniform BrickBlock` in shaders/common.glsl: the brick a slice piece samples.
struct BrickBlock {
  glm::vec3 origin;  // the voxel in texel 0
  float pad0;
  glm::vec3 texPerVoxel;  // 1 / the brick textures' size
  float pad1;
  glm::vec3 low;  // the sample positions it owns, [low, high)
  float isFirst;
  glm::vec3 high;
  float pad2;
};
static_assert(offsetof(BrickBlock, texPerVoxel) == 16);
static_assert(offsetof(BrickBlock, low) == 32);
static_assert(offsetof(BrickBlock, isFirst) == 44);
static_assert(offsetof(BrickBlock, high) == 48);

inline constexpr GLuint kFrameBlockBinding = 0;
inline constexpr GLuint kSliceBlockBinding = 1;
inline constexpr GLuint kSliceRangeBinding = 2;  // tile_march.glsl `uniform SliceRange`
inline constexpr GLuint kBrickBlockBinding = 3;

class FrameUniforms {
 public:
  FrameUniforms();
  // The frame's block and one block per slice of `plan`, uploaded in one call each.
  void upload(const View& view, glm::ivec3 dims, const SlicePlan& plan);
  // Binds slice k's block (and the frame's block) to their binding points.
  void bindSlice(int k) const;
  // For passes that read no slice (screen passes): slice 0's block, or nothing to read.
  void bindFrame() const;
  // One block per brick of the volume's layout (once per volume), and binding brick b's.
  void uploadBricks(const BrickLayout& layout);
  void bindBrick(std::size_t brick) const;

  // The tile march's view: slices [first, first + slicesPerRange()) as one uniform block at
  // kSliceRangeBinding, slice first + i from vec4 i * sliceStrideVec4() on. As many as fit in a
  // uniform block (GL_MAX_UNIFORM_BLOCK_SIZE); the buffer is padded so that every range is
  // whole, its slices past the plan's last unused.
  void bindSliceRange(int first) const;
  int slicesPerRange() const { return slicesPerRange_; }
  int sliceStrideVec4() const { return int(sliceStride_ / 16); }

 private:
  gl::BufferName frameBuffer_;
  gl::BufferName sliceBuffer_;
  gl::BufferName brickBuffer_;
  GLsizeiptr brickStride_ = 0;
  // sizeof(SliceBlock) rounded up to the offset alignment, and to whole vec4s (the range view)
  GLsizeiptr sliceStride_ = 0;
  int slicesPerRange_ = 0;
  int slices_ = 0;
};

}  // namespace vsil
