#include "slicing/compositing.h"

#include "slicing/gl_state.h"
#include "slicing/hit_records.h"

namespace vsil {

void FrontToBackCompositor::beginFrame(const FrameContext& frame) {
  const glm::ivec2 size = frame.view->viewport;
  if (!targets_ || targets_->color.size() != size) {
    targets_.reset();
    gl::RenderTarget color(size, GL_RGBA32F, /*withDepthStencil=*/true);
    const GLuint depth = color.depthStencil();
    targets_.emplace(Targets{std::move(color), gl::EmptyFramebuffer(size, depth)});
  }
  // Off: only pixels past their exit are retired (no opacity reaches 2).
  deadOpacity_ = frame.settings->earlyRayTermination ? kTerminationOpacity : 2.0f;
  gl::Capability noScissor(GL_SCISSOR_TEST, false);
  const GLfloat transparent[4] = {0, 0, 0, 0};
  targets_->color.bindForDrawing();
  VSIL_GL(glClearBufferfv(GL_COLOR, 0, transparent));
  frame.emptySpace->writeEntryDepth(glm::mat4(frame.view->clipFromVoxel()));
}

void FrontToBackCompositor::drawSlice(const FrameContext& frame, const SliceContext& slice,
                                      gl::Program& program,
                                      const std::vector<gl::TextureName>* auxiliaryBricks) {
  if (slice.vertexCount == 0) return;
  targets_->color.bindForDrawing();
  {
    // GREATER, no depth writes: skips empty space in front and retired pixels, early.
    gl::DepthTest skipEmptyAndDead(GL_GREATER, /*write=*/false);
    gl::Blending behind(GL_FUNC_ADD, GL_ONE_MINUS_DST_ALPHA, GL_ONE);
    program.use();
    drawSlicePolygon(frame, slice, auxiliaryBricks);
  }
  if (slice.index % kMarkDeadInterval == kMarkDeadInterval - 1) {
    markDeadPixels(frame, slice, targets_->depthOnly, targets_->color, DeadRule::Opacity,
                   deadOpacity_);
  }
}

cv::Mat4f FrontToBackCompositor::readBack() const {
  return readTargetFlipped(targets_->color, 4);
}

float FrontToBackCompositor::opacityExponent(const FrameContext& frame) {
  return float(frame.plan->stepVoxels);
}

}  // namespace vsil
