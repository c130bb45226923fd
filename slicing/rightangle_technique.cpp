#include "slicing/rightangle_technique.h"

namespace vsil {

void RightAngleTechnique::beginFrame(const FrameContext& frame) {
  const glm::ivec2 size = frame.view->viewport;
  if (!targets_ || targets_->result.size() != size) {
    targets_.reset();
    targets_.emplace(Targets{gl::RenderTarget(size, GL_RGBA32F, /*withDepthStencil=*/true),
                             gl::RenderTarget(size, GL_RGBA32F)});
  }
  if (!program_) program_.emplace("slice.vert", "rightangle.frag");
  if (!finish_) finish_.emplace("screen.vert", "finish.frag", "#define RIGHT_ANGLE_LINES 1");
  glDisable(GL_SCISSOR_TEST);
  const GLfloat zero[4] = {0, 0, 0, 0};
  targets_->result.bindForDrawing();
  VSIL_GL(glClearBufferfv(GL_COLOR, 0, zero));
  VSIL_GL(glClearBufferfi(GL_DEPTH_STENCIL, 0, 1.0f, 0));
  program_->use();
  setSliceUniforms(*program_, frame, nullptr);
}

void RightAngleTechnique::drawSlice(const FrameContext& frame, const SliceContext& slice) {
  if (slice.vertexCount == 0) return;
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  program_->set("sliceEyeDistance", float(slice.slice->eyeDistance));
  program_->set("sliceDepth", float(slice.slice->depth));
  glBindVertexArray(frame.sliceVertexArray);
  VSIL_GL(glDrawArrays(GL_TRIANGLE_FAN, slice.firstVertex, slice.vertexCount));
}

void RightAngleTechnique::endFrame(const FrameContext& frame) {
  glDisable(GL_DEPTH_TEST);
  finishRecords(*finish_, frame, targets_->result, targets_->finished);
}

FrameBuffers RightAngleTechnique::readBack(const FrameContext&) {
  return frameFromStateImage(readTargetFlipped(targets_->finished, 4));
}

}  // namespace vsil
