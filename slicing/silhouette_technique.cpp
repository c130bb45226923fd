#include "slicing/silhouette_technique.h"

#include "slicing/rightangle_technique.h"

namespace vsil {
namespace {

// PixelRect (top-down pixels) to a GL scissor box (bottom-up).
void scissorTo(const PixelRect& rect, glm::ivec2 viewport) {
  glScissor(rect.x0, viewport.y - rect.y1, rect.x1 - rect.x0, rect.y1 - rect.y0);
}

}  // namespace

void SilhouetteTechnique::beginFrame(const FrameContext& frame) {
  const glm::ivec2 size = frame.view->viewport;
  if (!targets_ || targets_->footprint.size() != size) {
    targets_.reset();
    targets_.emplace(Targets{gl::RenderTarget(size, GL_R8UI), gl::RenderTarget(size, GL_R8UI),
                             {gl::RenderTarget(size, GL_RGBA32F),
                              gl::RenderTarget(size, GL_RGBA32F)}});
  }
  if (!programs_) programs_.emplace();
  const GLuint zeroU[4] = {0, 0, 0, 0};
  const GLfloat zeroF[4] = {0, 0, 0, 0};
  glDisable(GL_SCISSOR_TEST);
  for (const gl::RenderTarget* target : {&targets_->footprint, &targets_->contour}) {
    target->bindForDrawing();
    VSIL_GL(glClearBufferuiv(GL_COLOR, 0, zeroU));
  }
  for (const auto& target : targets_->intermediate) {
    target.bindForDrawing();
    VSIL_GL(glClearBufferfv(GL_COLOR, 0, zeroF));
  }
  current_ = 0;
  previousSliceDepth_ = 0;
}

void SilhouetteTechnique::drawSlice(const FrameContext& frame, const SliceContext& slice) {
  const glm::ivec2 viewport = frame.view->viewport;
  if (slice.vertexCount == 0 || slice.changeBounds.empty()) {
    // The plane misses the box: every c is EMPTY.
    decide(frame, slice.slice, previousSliceDepth_, slice.changeBounds, true);
    previousSliceDepth_ = slice.slice->depth;
    return;
  }
  glEnable(GL_SCISSOR_TEST);
  scissorTo(slice.changeBounds, viewport);

  // 1. Footprint: clear the region, then the alpha-tested slice polygon.
  const GLuint zeroU[4] = {0, 0, 0, 0};
  targets_->footprint.bindForDrawing();
  VSIL_GL(glClearBufferuiv(GL_COLOR, 0, zeroU));
  programs_->footprint.use();
  setSliceUniforms(programs_->footprint, frame, slice.slice);
  glBindVertexArray(frame.sliceVertexArray);
  VSIL_GL(glDrawArrays(GL_TRIANGLE_FAN, slice.firstVertex, slice.vertexCount));

  // 2. Contour of the footprint.
  targets_->contour.bindForDrawing();
  programs_->contour.use();
  programs_->contour.set("footprintTexture", 1);
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_2D, targets_->footprint.texture());
  glBindVertexArray(frame.screenVertexArray);
  VSIL_GL(glDrawArrays(GL_TRIANGLES, 0, 3));

  // 3. Decision table into the other intermediate target.
  decide(frame, slice.slice, previousSliceDepth_, slice.changeBounds, false);
  previousSliceDepth_ = slice.slice->depth;
}

void SilhouetteTechnique::decide(const FrameContext& frame, const Slice* slice,
                                 double previousDepth, const PixelRect& bounds, bool emptySlice) {
  const glm::ivec2 viewport = frame.view->viewport;
  glEnable(GL_SCISSOR_TEST);
  scissorTo(bounds.empty() ? PixelRect{0, 0, viewport.x, viewport.y} : bounds, viewport);
  const int next = 1 - current_;
  targets_->intermediate[next].bindForDrawing();
  gl::Program& program = programs_->decision;
  program.use();
  setSliceUniforms(program, frame, slice);
  program.set("contourTexture", 1);
  program.set("intermediateTexture", 2);
  program.set("emptySlice", emptySlice ? 1 : 0);
  program.set("previousSliceDepth", float(previousDepth));
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_2D, targets_->contour.texture());
  glActiveTexture(GL_TEXTURE2);
  glBindTexture(GL_TEXTURE_2D, targets_->intermediate[current_].texture());
  glBindVertexArray(frame.screenVertexArray);
  VSIL_GL(glDrawArrays(GL_TRIANGLES, 0, 3));
  glActiveTexture(GL_TEXTURE0);
  current_ = next;
}

void SilhouetteTechnique::endFrame(const FrameContext& frame) {
  // The extra empty slice, over the whole image: contours reaching the back become silhouettes.
  Slice behind;
  if (!frame.plan->slices.empty()) {
    behind = Slice{frame.plan->slices.back().eyeDistance + frame.plan->stepEye,
                   frame.plan->slices.back().depth, {}};
  }
  const glm::ivec2 viewport = frame.view->viewport;
  decide(frame, &behind, previousSliceDepth_, PixelRect{0, 0, viewport.x, viewport.y}, true);
}

FrameBuffers SilhouetteTechnique::readBack(const FrameContext&) {
  return frameFromStateImage(readTargetFlipped(targets_->intermediate[current_], 4));
}

}  // namespace vsil
