#include "slicing/silhouette_technique.h"

#include "slicing/rightangle_technique.h"

namespace vsil {
namespace {

// PixelRect (top-down pixels) to a GL scissor box (bottom-up).
void scissorTo(const PixelRect& rect, glm::ivec2 viewport) {
  glEnable(GL_SCISSOR_TEST);
  glScissor(rect.x0, viewport.y - rect.y1, rect.x1 - rect.x0, rect.y1 - rect.y0);
}

PixelRect wholeImage(glm::ivec2 viewport) { return {0, 0, viewport.x, viewport.y}; }

constexpr GLuint kZeroU[4] = {0, 0, 0, 0};
constexpr GLfloat kZeroF[4] = {0, 0, 0, 0};

}  // namespace

void SilhouetteTechnique::beginFrame(const FrameContext& frame) {
  const glm::ivec2 size = frame.view->viewport;
  if (!targets_ || targets_->footprint.size() != size) {
    targets_.reset();
    targets_.emplace(Targets{gl::RenderTarget(size, GL_R8UI), gl::RenderTarget(size, GL_R8UI),
                             {gl::RenderTarget(size, GL_RGBA32F),
                              gl::RenderTarget(size, GL_RGBA32F)},
                             gl::EmptyFramebuffer(size)});
  }
  if (!programs_) programs_.emplace();
  pipeline_ = frame.settings->silhouettePipeline;
  glDisable(GL_SCISSOR_TEST);
  for (const gl::RenderTarget* target : {&targets_->footprint, &targets_->contour}) {
    target->bindForDrawing();
    VSIL_GL(glClearBufferuiv(GL_COLOR, 0, kZeroU));
  }
  for (const auto& target : targets_->intermediate) {
    target.bindForDrawing();
    VSIL_GL(glClearBufferfv(GL_COLOR, 0, kZeroF));
  }
  current_ = 0;
  previousSliceDepth_ = 0;
}

void SilhouetteTechnique::drawSlice(const FrameContext& frame, const SliceContext& slice) {
  const glm::ivec2 viewport = frame.view->viewport;
  const bool paper = pipeline_ == SilhouettePipeline::Paper;
  // Pixels whose record may change here: this polygon (c != EMPTY) and the previous one
  // (contours there meet c = EMPTY). The ping-pong targets must also agree outside the pass,
  // which needs the slice before that too. One pixel more for the contour's neighbourhood.
  const PixelRect bounds = slice.recentUnion(paper ? 3 : 2, 1, viewport);
  if (slice.vertexCount == 0) {
    // The plane misses the box: every c is EMPTY.
    decide(frame, slice.slice, bounds.empty() ? wholeImage(viewport) : bounds, true);
  } else {
    drawFootprint(frame, slice, bounds);
    if (paper) {
      // Contour of the footprint into its own target.
      targets_->contour.bindForDrawing();
      programs_->contour.use();
      programs_->contour.set("footprintTexture", 1);
      glActiveTexture(GL_TEXTURE1);
      glBindTexture(GL_TEXTURE_2D, targets_->footprint.texture());
      glBindVertexArray(frame.screenVertexArray);
      VSIL_GL(glDrawArrays(GL_TRIANGLES, 0, 3));
    }
    decide(frame, slice.slice, bounds, false);
  }
  previousSliceDepth_ = slice.slice->depth;
}

void SilhouetteTechnique::drawFootprint(const FrameContext& frame, const SliceContext& slice,
                                        const PixelRect& clearBounds) {
  // Everything the next passes read outside this polygon must be EMPTY: clear their region.
  scissorTo(clearBounds, frame.view->viewport);
  targets_->footprint.bindForDrawing();
  VSIL_GL(glClearBufferuiv(GL_COLOR, 0, kZeroU));
  programs_->footprint.use();
  setSliceUniforms(programs_->footprint, frame, slice.slice);
  glBindVertexArray(frame.sliceVertexArray);
  VSIL_GL(glDrawArrays(GL_TRIANGLE_FAN, slice.firstVertex, slice.vertexCount));
}

void SilhouetteTechnique::decide(const FrameContext& frame, const Slice* slice,
                                 const PixelRect& bounds, bool emptySlice) {
  if (pipeline_ == SilhouettePipeline::Paper) {
    decidePaper(frame, slice, bounds, emptySlice);
  } else {
    decideInPlace(frame, slice, bounds, emptySlice);
  }
}

void SilhouetteTechnique::decidePaper(const FrameContext& frame, const Slice* slice,
                                      const PixelRect& bounds, bool emptySlice) {
  scissorTo(bounds, frame.view->viewport);
  const int next = 1 - current_;
  targets_->intermediate[next].bindForDrawing();
  gl::Program& program = programs_->decision;
  program.use();
  setSliceUniforms(program, frame, slice);
  program.set("contourTexture", 1);
  program.set("intermediateTexture", 2);
  program.set("emptySlice", emptySlice ? 1 : 0);
  program.set("previousSliceDepth", float(previousSliceDepth_));
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_2D, targets_->contour.texture());
  glActiveTexture(GL_TEXTURE2);
  glBindTexture(GL_TEXTURE_2D, targets_->intermediate[current_].texture());
  glBindVertexArray(frame.screenVertexArray);
  VSIL_GL(glDrawArrays(GL_TRIANGLES, 0, 3));
  glActiveTexture(GL_TEXTURE0);
  current_ = next;
}

void SilhouetteTechnique::decideInPlace(const FrameContext& frame, const Slice* slice,
                                        const PixelRect& bounds, bool emptySlice) {
  scissorTo(bounds, frame.view->viewport);
  targets_->imageOnly.bindForDrawing();
  gl::Program& program = programs_->decisionInPlace;
  program.use();
  setSliceUniforms(program, frame, slice);
  program.set("intermediateImage", 0);
  program.set("footprintTexture", 1);
  program.set("intermediateTexture", 2);
  program.set("emptySlice", emptySlice ? 1 : 0);
  program.set("previousSliceDepth", float(previousSliceDepth_));
  gl::bindImage(0, targets_->intermediate[0]);
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_2D, targets_->footprint.texture());
  glActiveTexture(GL_TEXTURE2);
  glBindTexture(GL_TEXTURE_2D, targets_->intermediate[0].texture());
  glActiveTexture(GL_TEXTURE0);
  glBindVertexArray(frame.screenVertexArray);
  VSIL_GL(glDrawArrays(GL_TRIANGLES, 0, 3));
  // The next slice's fetches see what this one stored.
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
}

void SilhouetteTechnique::endFrame(const FrameContext& frame) {
  // The extra empty slice, over the whole image: contours reaching the back become silhouettes.
  Slice behind;
  if (!frame.plan->slices.empty()) {
    behind = Slice{frame.plan->slices.back().eyeDistance + frame.plan->stepEye,
                   frame.plan->slices.back().depth, {}};
  }
  decide(frame, &behind, wholeImage(frame.view->viewport), true);
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
  finishRecords(programs_->finish, frame, targets_->intermediate[current_],
                targets_->intermediate[1 - current_]);
  current_ = 1 - current_;
}

FrameBuffers SilhouetteTechnique::readBack(const FrameContext&) {
  return frameFromStateImage(readTargetFlipped(targets_->intermediate[current_], 4));
}

}  // namespace vsil
