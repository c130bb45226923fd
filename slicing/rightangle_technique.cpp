#include "slicing/rightangle_technique.h"

namespace vsil {

void RightAngleTechnique::beginFrame(const FrameContext& frame) {
  const glm::ivec2 size = frame.view->viewport;
  if (!targets_ || targets_->result.size() != size) {
    targets_.reset();
    gl::RenderTarget result(size, GL_RGBA32F, /*withDepthStencil=*/true);
    const GLuint depth = result.depthStencil();
    targets_.emplace(Targets{std::move(result), gl::RenderTarget(size, GL_RGBA32F),
                             gl::EmptyFramebuffer(size, depth)});
  }
  if (!program_) program_.emplace("slice.vert", "rightangle.frag");
  if (!finish_) finish_.emplace("screen.vert", "finish.frag", "#define RIGHT_ANGLE_LINES 1");
  if (!markDead_) markDead_.emplace("slice.vert", "mark_dead.frag", "#define OWN_RECORD_ONLY 1");
  glDisable(GL_SCISSOR_TEST);
  const GLfloat zero[4] = {0, 0, 0, 0};
  targets_->result.bindForDrawing();
  VSIL_GL(glClearBufferfv(GL_COLOR, 0, zero));
  frame.emptySpace->writeEntryDepth(glm::mat4(frame.view->clipFromVoxel()));
}

void RightAngleTechnique::drawSlice(const FrameContext& frame, const SliceContext& slice) {
  if (slice.vertexCount == 0) return;
  targets_->result.bindForDrawing();
  // GREATER, no depth writes: skips empty space in front (empty_space.h) and dead pixels,
  // early. The blending keeps each pixel's first hit (rightangle.frag).
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_GREATER);
  glDepthMask(GL_FALSE);
  glEnable(GL_BLEND);
  glBlendFunc(GL_ONE_MINUS_DST_ALPHA, GL_DST_ALPHA);
  program_->use();
  setSliceUniforms(*program_, frame, slice.slice);
  glBindVertexArray(frame.sliceVertexArray);
  VSIL_GL(glDrawArrays(GL_TRIANGLE_FAN, slice.firstVertex, slice.vertexCount));
  glDisable(GL_BLEND);
  if (slice.index % kMarkDeadInterval == kMarkDeadInterval - 1) {
    markDeadPixels(*markDead_, frame, slice, targets_->depthOnly, targets_->result);
  }
}

void RightAngleTechnique::endFrame(const FrameContext& frame) {
  glDisable(GL_DEPTH_TEST);
  finishRecords(*finish_, frame, targets_->result, targets_->finished);
}

FrameBuffers RightAngleTechnique::readBack(const FrameContext&) {
  return frameFromStateImage(readTargetFlipped(targets_->finished, 4));
}

}  // namespace vsil
