#include "slicing/techniques/firsthit/firsthit_technique.h"

#include <cmath>
#include <limits>

#include "slicing/gl_state.h"
#include "slicing/hit_records.h"

namespace vsil {

TechniqueInfo firstHitTechniqueInfo() {
  return {"firsthit",
          "the depth of the first iso-surface hit as grey (near white, far black), and as depth",
          {isoOption()},
          FrameOutputs{.state = false, .color = true, .depth = true},
          [] { return std::make_unique<FirstHitTechnique>(); }};
}

BrickOccupancy FirstHitTechnique::occupancy(const FrameContext& frame) const {
  return reachesIso(float(frame.options->number("iso")));
}

void FirstHitTechnique::beginFrame(const FrameContext& frame) {
  const glm::ivec2 size = frame.view->viewport;
  if (!targets_ || targets_->record.size() != size) {
    targets_.reset();
    gl::RenderTarget record(size, GL_RGBA32F, /*withDepthStencil=*/true);
    const GLuint depth = record.depthStencil();
    targets_.emplace(Targets{std::move(record), gl::EmptyFramebuffer(size, depth)});
  }
  slicePass_ = &frame.programs->get(
      gl::slicePassProgram(hitRecordSources(), "techniques/firsthit/firsthit.frag"));
  slicePass_->use();
  slicePass_->set("isoValue", float(frame.options->number("iso")));
  const GLfloat zero[4] = {0, 0, 0, 0};
  targets_->record.bindForDrawing();
  VSIL_GL(glClearBufferfv(GL_COLOR, 0, zero));
  frame.emptySpace->writeEntryDepth(glm::mat4(frame.view->clipFromVoxel()));
}

void FirstHitTechnique::drawSlice(const FrameContext& frame, const SliceContext& slice) {
  if (slice.vertexCount == 0) return;
  targets_->record.bindForDrawing();
  {
    gl::DepthTest skipEmptyAndDead(GL_GREATER, /*write=*/false);
    gl::Blending keepFirstHit(GL_FUNC_ADD, GL_ONE_MINUS_DST_ALPHA, GL_DST_ALPHA);
    slicePass_->use();
    drawSlicePolygon(frame, slice);
  }
  if (slice.index % kMarkDeadInterval == kMarkDeadInterval - 1) {
    markDeadPixels(frame, slice, targets_->depthOnly, targets_->record, /*neighboursFinal=*/false);
  }
}

FrameBuffers FirstHitTechnique::readBack(const FrameContext&) {
  const cv::Mat records = readTargetFlipped(targets_->record, 4);
  FrameBuffers frame;
  frame.depth.create(records.rows, records.cols);
  frame.color.create(records.rows, records.cols);
  for (int y = 0; y < records.rows; ++y) {
    const cv::Vec4f* record = records.ptr<cv::Vec4f>(y);
    for (int x = 0; x < records.cols; ++x) {
      const bool hit = record[x][3] > 0.5f;
      const float depth = record[x][1];
      const float grey = 1.0f - depth;
      frame.depth(y, x) = hit ? depth : std::numeric_limits<float>::quiet_NaN();
      frame.color(y, x) = hit ? cv::Vec4f(grey, grey, grey, 1.0f) : cv::Vec4f(0, 0, 0, 0);
    }
  }
  return frame;
}

}  // namespace vsil
