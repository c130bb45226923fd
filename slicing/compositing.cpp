#include "slicing/compositing.h"

#include <algorithm>

#include "slicing/gl_state.h"
#include "slicing/hit_records.h"
#include "slicing/tile_march.h"

namespace vsil {

void FrontToBackCompositor::beginFrame(const FrameContext& frame, SlicingPipeline pipeline) {
  const glm::ivec2 size = frame.view->viewport;
  if (!targets_ || targets_->color.size() != size) {
    targets_.reset();
    gl::RenderTarget color(size, GL_RGBA32F, /*withDepthStencil=*/true);
    const GLuint depth = color.depthStencil();
    targets_.emplace(Targets{std::move(color), gl::EmptyFramebuffer(size, depth)});
  }
  // Off: only pixels past their exit are retired (no opacity reaches 2).
  deadOpacity_ = frame.settings->earlyRayTermination ? kTerminationOpacity : 2.0f;
  pipeline_ = pipeline;
  if (pipeline == SlicingPipeline::Tiles) return;
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
  const bool skipping = pipeline_ != SlicingPipeline::Paper;
  {
    // GREATER, no depth writes: skips empty space in front and retired pixels, early. The
    // paper pipeline draws every pixel of the polygon.
    gl::DepthTest skipEmptyAndDead(skipping ? GL_GREATER : GL_ALWAYS, /*write=*/false);
    gl::Blending behind(GL_FUNC_ADD, GL_ONE_MINUS_DST_ALPHA, GL_ONE);
    program.use();
    drawSlicePolygon(frame, slice, auxiliaryBricks);
  }
  if (skipping && slice.index % kMarkDeadInterval == kMarkDeadInterval - 1) {
    markDeadPixels(frame, slice, targets_->depthOnly, targets_->color, DeadRule::Opacity,
                   deadOpacity_);
  }
}

namespace {
// Dispatches of whole groups of kMarkDeadInterval slices: a pixel found opaque when one starts
// was then retired at the last group's end, as drawSlice's marks retire it.
MarchShape compositingMarchShape(const FrameContext& frame) {
  MarchShape shape;
  shape.slicesPerDispatch = std::max(
      kMarkDeadInterval, frame.uniforms->slicesPerRange() / kMarkDeadInterval * kMarkDeadInterval);
  return shape;
}
}  // namespace

gl::Program& FrontToBackCompositor::marchProgram(const FrameContext& frame,
                                                 const std::vector<std::string>& shared,
                                                 const std::string& computeFile,
                                                 std::vector<std::string> defines) {
  defines.push_back("MARK_DEAD_INTERVAL " + std::to_string(kMarkDeadInterval));
  return vsil::marchProgram(frame, shared, computeFile, compositingMarchShape(frame),
                            std::move(defines));
}

void FrontToBackCompositor::march(const FrameContext& frame, gl::Program& program) {
  program.use();
  program.set("deadOpacity", deadOpacity_);
  runMarch(frame, program, compositingMarchShape(frame), targets_->color);
}

cv::Mat4f FrontToBackCompositor::readBack() const {
  return readTargetFlipped(targets_->color, 4);
}

float FrontToBackCompositor::opacityExponent(const FrameContext& frame) {
  return float(frame.plan->stepVoxels);
}

}  // namespace vsil
