#include "slicing/techniques/rightangle/rightangle_technique.h"

#include "slicing/gl_state.h"
#include "slicing/hit_records.h"

namespace vsil {

TechniqueInfo rightAngleTechniqueInfo() {
  OptionSpec exponent;
  exponent.name = "ra-exponent";
  exponent.help = "exponent k of the line test (1 - |n.v|)^k > threshold";
  exponent.defaultValue = 8.0;
  exponent.min = 0;
  exponent.minExclusive = true;
  OptionSpec threshold;
  threshold.name = "ra-threshold";
  threshold.help = "a first hit is a line pixel where (1 - |n.v|)^k exceeds this";
  threshold.defaultValue = 0.3;
  return {"rightangle",
          "the right-angle line test on the first iso-surface hit (RA, the Nagy–Klein baseline)",
          {isoOption(), exponent, threshold},
          FrameOutputs{.state = true, .color = false, .depth = true},
          [] { return std::make_unique<RightAngleTechnique>(); }};
}

BrickOccupancy RightAngleTechnique::occupancy(const FrameContext& frame) const {
  return reachesIso(float(frame.options->number("iso")));
}

void RightAngleTechnique::beginFrame(const FrameContext& frame) {
  const glm::ivec2 size = frame.view->viewport;
  if (!targets_ || targets_->record.size() != size) {
    targets_.reset();
    gl::RenderTarget record(size, GL_RGBA32F, /*withDepthStencil=*/true);
    const GLuint depth = record.depthStencil();
    targets_.emplace(Targets{std::move(record), gl::RenderTarget(size, GL_RGBA32F),
                             gl::EmptyFramebuffer(size, depth)});
  }
  slicePass_ =
      &frame.programs->get(gl::slicePassProgram(hitRecordSources(), "techniques/rightangle/rightangle.frag"));
  slicePass_->use();
  slicePass_->set("isoValue", float(frame.options->number("iso")));
  finish_ = &finishProgram(frame, {"techniques/rightangle/rightangle.glsl"});
  finish_->use();
  finish_->set("rightAngleExponent", float(frame.options->number("ra-exponent")));
  finish_->set("rightAngleThreshold", float(frame.options->number("ra-threshold")));

  glDisable(GL_SCISSOR_TEST);
  const GLfloat zero[4] = {0, 0, 0, 0};
  targets_->record.bindForDrawing();
  VSIL_GL(glClearBufferfv(GL_COLOR, 0, zero));
  frame.emptySpace->writeEntryDepth(glm::mat4(frame.view->clipFromVoxel()));
}

void RightAngleTechnique::drawSlice(const FrameContext& frame, const SliceContext& slice) {
  if (slice.vertexCount == 0) return;
  targets_->record.bindForDrawing();
  {
    // GREATER, no depth writes: skips empty space in front (empty_space.h) and dead pixels,
    // early. The blending keeps each pixel's first hit (rightangle.frag).
    gl::DepthTest depthTest(GL_GREATER, /*write=*/false);
    gl::Blending keepFirstHit(GL_FUNC_ADD, GL_ONE_MINUS_DST_ALPHA, GL_DST_ALPHA);
    slicePass_->use();
    drawSlicePolygon(frame, slice);
  }
  if (slice.index % kMarkDeadInterval == kMarkDeadInterval - 1) {
    markDeadPixels(frame, slice, targets_->depthOnly, targets_->record, /*neighboursFinal=*/false);
  }
}

void RightAngleTechnique::endFrame(const FrameContext& frame) {
  finishRecords(frame, *finish_, targets_->record, targets_->finished);
}

FrameBuffers RightAngleTechnique::readBack(const FrameContext&) {
  return frameFromStateImage(readTargetFlipped(targets_->finished, 4));
}

}  // namespace vsil
