#include "slicing/silhouette_technique.h"

namespace vsil {
namespace {

// PixelRect (top-down pixels) to a GL scissor box (bottom-up).
void scissorTo(const PixelRect& rect, glm::ivec2 viewport) {
  glEnable(GL_SCISSOR_TEST);
  glScissor(rect.x0, viewport.y - rect.y1, rect.x1 - rect.x0, rect.y1 - rect.y0);
}

PixelRect wholeImage(glm::ivec2 viewport) {
  return {0, 0, viewport.x, viewport.y};
}

constexpr GLuint kZeroU[4] = {0, 0, 0, 0};
constexpr GLfloat kZeroF[4] = {0, 0, 0, 0};

}  // namespace

SilhouetteTechnique::Programs::Programs()
    : footprint("slice.vert", "footprint.frag"),
      contour("screen.vert", "contour.frag"),
      decision("screen.vert", "decision.frag"),
      decisionInPlace("slice.vert", "decision_inplace.frag"),
      finish("screen.vert", "finish.frag"),
      markDead("slice.vert", "mark_dead.frag") {}

void SilhouetteTechnique::beginFrame(const FrameContext& frame) {
  const glm::ivec2 size = frame.view->viewport;
  if (!targets_ || targets_->footprint.size() != size) {
    targets_.reset();
    gl::RenderTarget footprint(size, GL_R32UI, /*withDepthStencil=*/true);
    const GLuint depth = footprint.depthStencil();
    targets_.emplace(
        Targets{std::move(footprint),
                gl::RenderTarget(size, GL_R8UI),
                {gl::RenderTarget(size, GL_RGBA32F), gl::RenderTarget(size, GL_RGBA32F)},
                gl::EmptyFramebuffer(size, depth)});
  }
  if (!programs_) programs_.emplace();
  pipeline_ = frame.settings->silhouettePipeline;
  glDisable(GL_SCISSOR_TEST);
  for (const gl::RenderTarget* target : {&targets_->footprint, &targets_->contour}) {
    target->bindForDrawing();
    VSIL_GL(glClearBufferuiv(GL_COLOR, 0, kZeroU));
  }
  // The fast pipeline's footprint pass tests GREATER against this depth: pixels in front of
  // the first occupied brick, and dead pixels later, are skipped.
  targets_->footprint.bindForDrawing();
  frame.emptySpace->writeEntryDepth(glm::mat4(frame.view->clipFromVoxel()));
  for (const auto& target : targets_->intermediate) {
    target.bindForDrawing();
    VSIL_GL(glClearBufferfv(GL_COLOR, 0, kZeroF));
  }
  current_ = 0;
  previousSliceDepth_ = 0;
}

void SilhouetteTechnique::drawSlice(const FrameContext& frame, const SliceContext& slice) {
  const glm::ivec2 viewport = frame.view->viewport;
  if (pipeline_ == SilhouettePipeline::Fast) {
    if (slice.vertexCount > 0) {
      // Tagged with this slice, the footprint needs no clearing (common.glsl footprintTag).
      drawFootprint(frame, slice);
      // The decision reads the records the previous slice's decision stored. The barrier
      // comes after this footprint pass so that llvmpipe, which waits for all queued work at a
      // barrier, waits once per slice: the decision's read of the footprint then finds it done.
      glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
      decideInPlace(frame, slice);
      if (slice.index % kMarkDeadInterval == kMarkDeadInterval - 1) {
        glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);  // marking reads this slice's records
        markDeadPixels(programs_->markDead, frame, slice, targets_->depthOnly,
                       targets_->intermediate[0]);
      }
    }
  } else {
    // Pixels whose record may change here: this polygon (c != EMPTY) and the previous one
    // (contours there meet c = EMPTY); the ping-pong targets must also agree outside the pass,
    // which needs the slice before that too. One pixel more for the contour's neighbourhood.
    const PixelRect bounds = slice.recentUnion(3, 1, viewport);
    if (!bounds.empty()) {
      // Everything the next passes read outside this polygon must be EMPTY.
      scissorTo(bounds, viewport);
      targets_->footprint.bindForDrawing();
      VSIL_GL(glClearBufferuiv(GL_COLOR, 0, kZeroU));
      if (slice.vertexCount > 0) drawFootprint(frame, slice);
      contourPaper(frame, bounds);
      decidePaper(frame, slice.slice, bounds);
    }
  }
  previousSliceDepth_ = slice.slice->depth;
}

void SilhouetteTechnique::drawFootprint(const FrameContext& frame, const SliceContext& slice) {
  glDisable(GL_SCISSOR_TEST);
  targets_->footprint.bindForDrawing();
  if (pipeline_ == SilhouettePipeline::Fast) {
    // Slices come in depth order: GREATER passes every pixel but dead ones (depth 1), early;
    // FILLED fragments (not discarded) leave this slice's depth for the decision pass.
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_GREATER);
    glDepthMask(GL_TRUE);
  }
  programs_->footprint.use();
  setSliceUniforms(programs_->footprint, frame, slice.slice);
  programs_->footprint.set("footprintTag", footprintTag(slice));
  glBindVertexArray(frame.sliceVertexArray);
  VSIL_GL(glDrawArrays(GL_TRIANGLE_FAN, slice.firstVertex, slice.vertexCount));
  glDisable(GL_DEPTH_TEST);
}

void SilhouetteTechnique::contourPaper(const FrameContext& frame, const PixelRect& bounds) {
  scissorTo(bounds, frame.view->viewport);
  targets_->contour.bindForDrawing();
  programs_->contour.use();
  programs_->contour.set("footprintTag", 1u);
  programs_->contour.set("footprintTexture", 1);
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_2D, targets_->footprint.texture());
  glActiveTexture(GL_TEXTURE0);
  glBindVertexArray(frame.screenVertexArray);
  VSIL_GL(glDrawArrays(GL_TRIANGLES, 0, 3));
}

void SilhouetteTechnique::decidePaper(const FrameContext& frame, const Slice* slice,
                                      const PixelRect& bounds) {
  scissorTo(bounds, frame.view->viewport);
  const int next = 1 - current_;
  targets_->intermediate[next].bindForDrawing();
  gl::Program& program = programs_->decision;
  program.use();
  setSliceUniforms(program, frame, slice);
  program.set("contourTexture", 1);
  program.set("intermediateTexture", 2);
  program.set("emptySlice", slice ? 0 : 1);
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_2D, targets_->contour.texture());
  glActiveTexture(GL_TEXTURE2);
  glBindTexture(GL_TEXTURE_2D, targets_->intermediate[current_].texture());
  glActiveTexture(GL_TEXTURE0);
  glBindVertexArray(frame.screenVertexArray);
  VSIL_GL(glDrawArrays(GL_TRIANGLES, 0, 3));
  current_ = next;
}

void SilhouetteTechnique::decideInPlace(const FrameContext& frame, const SliceContext& slice) {
  glDisable(GL_SCISSOR_TEST);
  targets_->depthOnly.bindForDrawing();
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_EQUAL);
  glDepthMask(GL_FALSE);
  gl::Program& program = programs_->decisionInPlace;
  program.use();
  setSliceUniforms(program, frame, slice.slice);
  program.set("intermediateImage", 0);
  program.set("footprintTexture", 1);
  program.set("intermediateTexture", 2);
  program.set("previousSliceDepth", float(previousSliceDepth_));
  program.set("footprintTag", footprintTag(slice));
  gl::bindImage(0, targets_->intermediate[0]);
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_2D, targets_->footprint.texture());
  glActiveTexture(GL_TEXTURE2);
  glBindTexture(GL_TEXTURE_2D, targets_->intermediate[0].texture());
  glActiveTexture(GL_TEXTURE0);
  glBindVertexArray(frame.sliceVertexArray);
  VSIL_GL(glDrawArrays(GL_TRIANGLE_FAN, slice.firstVertex, slice.vertexCount));
  glDisable(GL_DEPTH_TEST);
}

void SilhouetteTechnique::endFrame(const FrameContext& frame) {
  if (pipeline_ == SilhouettePipeline::Paper) {
    // The extra empty slice, over the whole image: contours at the back become silhouettes.
    const PixelRect all = wholeImage(frame.view->viewport);
    decidePaper(frame, nullptr, all);
  }
  // (The fast pipeline's finishing pass turns remaining contours into silhouettes itself; it
  // reads the records the last decision stored.)
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
  finishRecords(programs_->finish, frame, targets_->intermediate[current_],
                targets_->intermediate[1 - current_]);
  current_ = 1 - current_;
}

FrameBuffers SilhouetteTechnique::readBack(const FrameContext&) {
  return frameFromStateImage(readTargetFlipped(targets_->intermediate[current_], 4));
}

}  // namespace vsil
