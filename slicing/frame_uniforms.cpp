#include "slicing/frame_uniforms.h"

#include <algorithm>
#include <cstring>
#include <vector>

namespace vsil {

FrameUniforms::FrameUniforms()
    : frameBuffer_(gl::createBuffer()),
      sliceBuffer_(gl::createBuffer()),
      brickBuffer_(gl::createBuffer()) {
  GLint alignment = 256;
  glGetIntegerv(GL_UNIFORM_BUFFER_OFFSET_ALIGNMENT, &alignment);
  alignment = std::max(alignment, GLint(16));  // a power of two: also whole vec4s
  brickStride_ = (GLsizeiptr(sizeof(BrickBlock)) + alignment - 1) / alignment * alignment;
  const GLsizeiptr size = sizeof(SliceBlock);
  sliceStride_ = (size + alignment - 1) / alignment * alignment;
  GLint maxBlockSize = 16384;  // the least GL 4.5 allows
  glGetIntegerv(GL_MAX_UNIFORM_BLOCK_SIZE, &maxBlockSize);
  slicesPerRange_ = std::max(1, int(maxBlockSize / sliceStride_));
}

void FrameUniforms::upload(const View& view, glm::ivec3 dims, const SlicePlan& plan) {
  FrameBlock frame{};
  frame.voxelFromEye = glm::mat4(glm::inverse(view.eyeFromVoxel));
  frame.clipFromVoxel = glm::mat4(view.clipFromVoxel());
  const glm::mat3 gradient(glm::transpose(glm::inverse(glm::dmat3(view.eyeFromVoxel))));
  for (int column = 0; column < 3; ++column) {
    frame.eyeFromVoxelGradient[column] = glm::vec4(gradient[column], 0.0f);
  }
  frame.volumeDims = glm::vec3(dims);
  frame.orthographic = view.orthographic ? 1 : 0;
  frame.viewportSize = glm::vec2(view.viewport);
  frame.halfExtent = glm::vec2(view.halfExtent);
  const PixelRays rays = pixelRays(view, plan);
  frame.rayOriginPerWindowX = rays.originPerWindowX;
  frame.rayStepEye = rays.stepEye;
  frame.rayOriginPerWindowY = glm::vec4(rays.originPerWindowY, 0.0f);
  frame.rayOriginAtWindowOrigin = glm::vec4(rays.originAtWindowOrigin, 0.0f);
  frame.rayDirectionPerWindowX = glm::vec4(rays.directionPerWindowX, 0.0f);
  frame.rayDirectionPerWindowY = glm::vec4(rays.directionPerWindowY, 0.0f);
  frame.rayDirectionAtWindowOrigin = rays.directionAtWindowOrigin;
  VSIL_GL(glBindBuffer(GL_UNIFORM_BUFFER, frameBuffer_.id()));
  VSIL_GL(glBufferData(GL_UNIFORM_BUFFER, sizeof(frame), &frame, GL_STREAM_DRAW));

  // At least one block, so that screen passes always have one bound; a range's worth more, so
  // that every slice range is whole.
  slices_ = int(plan.slices.size());
  std::vector<std::byte> blocks(std::size_t(sliceStride_) *
                                std::size_t(std::max(slices_, 1) + slicesPerRange_));
  for (int k = 0; k < slices_; ++k) {
    const Slice& slice = plan.slices[std::size_t(k)];
    const SliceVoxelCoords tex = sliceVoxelCoords(view, slice.eyeDistance);
    SliceBlock block{};
    block.voxelPerNdcX = tex.perNdcX;
    block.voxelPerNdcY = tex.perNdcY;
    block.voxelAtNdcOrigin = tex.atNdcOrigin;
    block.eyeDistance = float(slice.eyeDistance);
    block.depth = float(slice.depth);
    const glm::dvec4 clip = view.clipFromEye * glm::dvec4(0.0, 0.0, -slice.eyeDistance, 1.0);
    block.windowDepth = float(0.5 * clip.z / clip.w + 0.5);
    block.previousDepth = k > 0 ? float(plan.slices[std::size_t(k - 1)].depth) : 0.0f;
    block.index = std::uint32_t(k);
    std::memcpy(blocks.data() + std::size_t(k) * std::size_t(sliceStride_), &block, sizeof(block));
  }
  VSIL_GL(glBindBuffer(GL_UNIFORM_BUFFER, sliceBuffer_.id()));
  VSIL_GL(
      glBufferData(GL_UNIFORM_BUFFER, GLsizeiptr(blocks.size()), blocks.data(), GL_STREAM_DRAW));
  glBindBuffer(GL_UNIFORM_BUFFER, 0);
  bindFrame();
}

void FrameUniforms::bindSlice(int k) const {
  glBindBufferRange(GL_UNIFORM_BUFFER, kSliceBlockBinding, sliceBuffer_.id(),
                    GLintptr(k) * sliceStride_, sizeof(SliceBlock));
}

void FrameUniforms::bindSliceRange(int first) const {
  VSIL_GL(glBindBufferRange(GL_UNIFORM_BUFFER, kSliceRangeBinding, sliceBuffer_.id(),
                            GLintptr(first) * sliceStride_, slicesPerRange_ * sliceStride_));
}

void FrameUniforms::uploadBricks(const BrickLayout& layout) {
  std::vector<std::byte> blocks(std::size_t(brickStride_) *
                                std::max<std::size_t>(layout.size(), 1));
  for (std::size_t b = 0; b < layout.size(); ++b) {
    const Brick& brick = layout.bricks()[b];
    BrickBlock block{};
    block.origin = glm::vec3(brick.origin);
    block.texPerVoxel = 1.0f / glm::vec3(brick.size);  // exact: powers of two
    block.low = glm::vec3(brick.low);
    block.high = glm::vec3(brick.high);
    block.isFirst = b == 0 ? 1.0f : 0.0f;
    std::memcpy(blocks.data() + b * std::size_t(brickStride_), &block, sizeof(block));
  }
  VSIL_GL(glBindBuffer(GL_UNIFORM_BUFFER, brickBuffer_.id()));
  VSIL_GL(
      glBufferData(GL_UNIFORM_BUFFER, GLsizeiptr(blocks.size()), blocks.data(), GL_STATIC_DRAW));
  glBindBuffer(GL_UNIFORM_BUFFER, 0);
  bindBrick(0);
}

void FrameUniforms::bindBrick(std::size_t brick) const {
  glBindBufferRange(GL_UNIFORM_BUFFER, kBrickBlockBinding, brickBuffer_.id(),
                    GLintptr(brick) * brickStride_, sizeof(BrickBlock));
}

void FrameUniforms::bindFrame() const {
  glBindBufferBase(GL_UNIFORM_BUFFER, kFrameBlockBinding, frameBuffer_.id());
  bindSlice(0);
}

}  // namespace vsil
