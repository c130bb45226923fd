#include "slicing/techniques/mip/lmip_technique.h"

#include "slicing/gl_state.h"
#include "slicing/hit_records.h"
#include "slicing/illustration_options.h"
#include "slicing/slicer.h"
#include "slicing/techniques/mip/mip_options.h"
#include "slicing/techniques/mip/mip_technique.h"
#include "slicing/texture_units.h"
#include "slicing/tile_march.h"

namespace vsil {

TechniqueInfo lmipTechniqueInfo() {
  return {"lmip",
          "local MIP: the first local maximum above a threshold along each ray",
          {windowOption(), transferFunctionOption(), lmipThresholdOption()},
          FrameOutputs{.state = false, .color = true, .depth = true},
          [] { return std::make_unique<LmipTechnique>(); },
          /*usesGradients=*/false,
          /*checkValues=*/checkWindowOrTf,
          /*needsOneTexture=*/{}};
}

ResolvedOptions LmipTechnique::resolve(const FrameContext& frame) {
  ResolvedOptions resolved = resolveMipFamily(*frame.options);
  resolved.details["lmip_threshold"] = lmipThreshold(*frame.options);  // given or the window's
  return resolved;
}

BrickOccupancy LmipTechnique::occupancy(const FrameContext&) const {
  return [](ValueRange) { return true; };
}

namespace {
// One invocation per pixel, as the first-hit march: no pixel reads another's.
constexpr MarchShape kLmipMarchShape{{16, 16}, {16, 16}};
}  // namespace

bool LmipTechnique::marches(const FrameContext& frame) {
  return frame.volume->brickCount() == 1;
}

void LmipTechnique::beginFrame(const FrameContext& frame) {
  const glm::ivec2 size = frame.view->viewport;
  if (!targets_ || targets_->record.size() != size) {
    targets_.reset();
    gl::RenderTarget record(size, GL_RGBA32F, /*withDepthStencil=*/true);
    const GLuint depth = record.depthStencil();
    targets_.emplace(Targets{std::move(record), gl::EmptyFramebuffer(size, depth),
                             gl::RenderTarget(size, GL_RGBA32F)});
  }
  if (marches(frame)) return;  // the march runs after the (empty) sweep, in endFrame
  slicePass_ = &frame.programs->get(gl::slicePassProgram(
      hitRecordSources(), "techniques/mip/lmip_slice.frag", {kRaySamplingDefine}));
  slicePass_->use();
  slicePass_->set("lmipThreshold", lmipThreshold(*frame.options));
  gl::Capability noScissor(GL_SCISSOR_TEST, false);
  const GLfloat notFound[4] = {0, kNoSample, kNoSample, 0};
  targets_->record.bindForDrawing();
  VSIL_GL(glClearBufferfv(GL_COLOR, 0, notFound));
  frame.emptySpace->writeEntryDepth(glm::mat4(frame.view->clipFromVoxel()));
}

void LmipTechnique::drawSlice(const FrameContext& frame, const SliceContext& slice) {
  if (marches(frame) || slice.vertexCount == 0) return;
  {
    // The record's depth buffer without the record itself: the pass samples the record, so
    // it must not be drawn into as well; it writes through the image.
    targets_->depthOnly.bindForDrawing();
    gl::DepthTest skipRetired(GL_GREATER, /*write=*/false);
    slicePass_->use();
    gl::bindTexture(gl::TextureUnit::Record, GL_TEXTURE_2D, targets_->record.texture());
    gl::bindImage(gl::ImageUnit::Record, targets_->record);
    drawSlicePolygon(frame, slice);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);  // the next slice reads these records
  }
  if (slice.index % kMarkDeadInterval == kMarkDeadInterval - 1) {
    markDeadPixels(frame, slice, targets_->depthOnly, targets_->record, DeadRule::OwnRecord);
  }
}

void LmipTechnique::endFrame(const FrameContext& frame) {
  if (marches(frame)) {
    gl::Program& march =
        marchProgram(frame, hitRecordSources(), "techniques/mip/lmip_march.comp", kLmipMarchShape);
    march.use();
    march.set("lmipThreshold", lmipThreshold(*frame.options));
    march.set("noSample", kNoSample);
    runMarch(frame, march, kLmipMarchShape, targets_->record);
  }
  gl::Capability noScissor(GL_SCISSOR_TEST, false);
  gl::Program& finish =
      useMipFinish(frame, {"LMIP"}, targets_->record.texture(), targets_->colour, transferTable_);
  finish.set("lmipThreshold", lmipThreshold(*frame.options));
  drawScreen(frame);
}

FrameBuffers LmipTechnique::readBack(const FrameContext& frame) {
  const float threshold = lmipThreshold(*frame.options);
  // A depth where the ray met the threshold: the local maximum's.
  return colourWithDepth(
      targets_->colour, targets_->record, 3,
      [threshold](const cv::Vec4f& r) { return r[2] >= threshold; }, frame.settings->readDepth);
}

}  // namespace vsil
