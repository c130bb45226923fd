#include "slicing/hit_records.h"

#include <limits>
#include <stdexcept>

#include "slicing/compositing.h"
#include "slicing/gl_state.h"
#include "slicing/slicer.h"
#include "slicing/technique_table.h"
#include "slicing/texture_units.h"
#include "slicing/tile_march.h"

namespace vsil {

void markDeadPixels(const FrameContext& frame, const SliceContext& slice,
                    const gl::EmptyFramebuffer& depthOnly, const gl::RenderTarget& record,
                    DeadRule rule, float deadOpacity) {
  std::vector<std::string> defines;
  if (rule == DeadRule::NeighbourRecords) defines.emplace_back("NEIGHBOURS_FINAL");
  if (rule == DeadRule::Opacity) defines.emplace_back("OPACITY_DEAD");
  // A relayed slab's compositing (slab.h): marks only where the slice's sample lies in the slab
  // (the piece's brick owns it), so that a mark relayed to the slabs behind says the ray took
  // its last sample in front of them (mark_dead.frag SLAB_OWNED_MARKS).
  if (rule == DeadRule::Opacity && frame.slab) {
    const TechniqueInfo& info = findTechnique(frame.settings->technique);
    if (info.composition == Composition::Relay) {
      defines.emplace_back("SLAB_OWNED_MARKS");
      if (info.samplesOffPlanes) defines.emplace_back(kBoxAlignedSampling);
    }
  }
  gl::Program& markDead = frame.programs->get(
      gl::slicePassProgram(hitRecordSources(), "shaders/mark_dead.frag", defines));
  depthOnly.bindForDrawing();
  gl::Capability noScissor(GL_SCISSOR_TEST, false);
  gl::DepthTest depthTest(GL_GREATER, /*write=*/true);  // pixels already dead (depth 1) skipped
  gl::DepthRange everyFragmentAtOne(1.0, 1.0);
  markDead.use();
  if (rule == DeadRule::Opacity) markDead.set("deadOpacity", deadOpacity);
  gl::bindTexture(gl::TextureUnit::Record, GL_TEXTURE_2D, record.texture());
  gl::bindTexture(gl::TextureUnit::ExitDepth, GL_TEXTURE_2D, frame.emptySpace->exitDepthTexture());
  drawSlicePolygon(frame, slice);
}

namespace {
// The tiles walk's workgroup (first_hit_march.comp): no apron, since no pixel reads another's
// samples. 8x8 and 32x8 tiles measured within the noise of 16x16 (see kMarchShape in
// techniques/silhouette/silhouette_technique.cpp).
constexpr MarchShape kFirstHitMarchShape{{16, 16}, {16, 16}};
}  // namespace

void FirstHitRecorder::beginFrame(const FrameContext& frame, SlicingPipeline pipeline,
                                  std::optional<MaterialThreshold> material) {
  const glm::ivec2 size = frame.view->viewport;
  if (!targets_ || targets_->record.size() != size) {
    targets_.reset();
    gl::RenderTarget record(size, GL_RGBA32F, /*withDepthStencil=*/true);
    const GLuint depth = record.depthStencil();
    targets_.emplace(Targets{std::move(record), gl::EmptyFramebuffer(size, depth)});
  }
  pipeline_ = pipeline;
  if (pipeline_ == SlicingPipeline::Tiles) {
    requireOneBrick(frame, "--pipeline tiles", "use --pipeline fast or paper (the same pixels)");
    if (material) {
      throw std::logic_error("FirstHitRecorder: the tiles march has no material threshold");
    }
    // The march writes every pixel's record once: nothing to clear, no depth buffer.
    march_ = &marchProgram(frame, hitRecordSources(), "shaders/first_hit_march.comp",
                           kFirstHitMarchShape);
    march_->use();
    march_->set("isoValue", float(frame.options->number("iso")));
    return;
  }
  slicePass_ = &frame.programs->get(gl::slicePassProgram(
      hitRecordSources(), "shaders/first_hit.frag",
      // demip's second sweep samples where its march does.
      material ? std::vector<std::string>{"MATERIAL_THRESHOLD", kRaySamplingDefine}
               : std::vector<std::string>{}));
  slicePass_->use();
  if (material) {
    slicePass_->set("materialEps", material->materialEps);
    maximumTexture_ = material->maximumTexture;
  } else {
    slicePass_->set("isoValue", float(frame.options->number("iso")));
    maximumTexture_ = 0;
  }
  gl::Capability noScissor(GL_SCISSOR_TEST, false);
  const GLfloat zero[4] = {0, 0, 0, 0};
  targets_->record.bindForDrawing();
  VSIL_GL(glClearBufferfv(GL_COLOR, 0, zero));
  if (pipeline_ == SlicingPipeline::Fast) {
    frame.emptySpace->writeEntryDepth(glm::mat4(frame.view->clipFromVoxel()));
  }
}

void FirstHitRecorder::drawSlice(const FrameContext& frame, const SliceContext& slice) {
  if (pipeline_ == SlicingPipeline::Tiles || slice.vertexCount == 0) return;
  const bool skipping = pipeline_ == SlicingPipeline::Fast;
  targets_->record.bindForDrawing();
  {
    // GREATER, no depth writes: skips empty space in front (empty_space.h) and dead pixels,
    // early. The paper pipeline samples every pixel of the polygon. The blending keeps each
    // pixel's first hit (first_hit.frag).
    std::optional<gl::DepthTest> skipEmptyAndDead;
    if (skipping) skipEmptyAndDead.emplace(GL_GREATER, /*write=*/false);
    gl::Blending keepFirstHit(GL_FUNC_ADD, GL_ONE_MINUS_DST_ALPHA, GL_DST_ALPHA);
    slicePass_->use();
    if (maximumTexture_ != 0) {
      gl::bindTexture(gl::TextureUnit::Auxiliary0, GL_TEXTURE_2D, maximumTexture_);
    }
    drawSlicePolygon(frame, slice);
  }
  if (skipping && slice.index % kMarkDeadInterval == kMarkDeadInterval - 1) {
    markDeadPixels(frame, slice, targets_->depthOnly, targets_->record, DeadRule::OwnRecord);
  }
}

void FirstHitRecorder::endSlices(const FrameContext& frame) {
  if (pipeline_ == SlicingPipeline::Tiles)
    runMarch(frame, *march_, kFirstHitMarchShape, targets_->record);
}

gl::Program& finishProgram(const FrameContext& frame, const std::vector<std::string>& shared) {
  std::vector<std::string> sources = hitRecordSources();
  sources.insert(sources.end(), shared.begin(), shared.end());
  return frame.programs->get(gl::screenPassProgram(sources, "shaders/finish_hits.frag"));
}

void finishRecords(const FrameContext& frame, gl::Program& finish, const gl::RenderTarget& record,
                   const gl::RenderTarget& output) {
  output.bindForDrawing();
  gl::Capability noScissor(GL_SCISSOR_TEST, false);
  finish.use();
  gl::bindTexture(gl::TextureUnit::Record, GL_TEXTURE_2D, record.texture());
  // Each brick's pass shades the hits its brick owns (finish_hits.frag).
  drawScreenPerBrick(frame);
}

FrameBuffers frameFromStateImage(const cv::Mat& stateDepthShade) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  FrameBuffers frame;
  frame.state.create(stateDepthShade.rows, stateDepthShade.cols);
  frame.depth.create(stateDepthShade.rows, stateDepthShade.cols);
  frame.shade.create(stateDepthShade.rows, stateDepthShade.cols);
  for (int y = 0; y < stateDepthShade.rows; ++y) {
    const cv::Vec4f* row = stateDepthShade.ptr<cv::Vec4f>(y);
    for (int x = 0; x < stateDepthShade.cols; ++x) {
      const auto state = PixelState(std::uint8_t(row[x][0] + 0.5f));
      frame.state(y, x) = std::uint8_t(state);
      frame.depth(y, x) = state == PixelState::Empty ? nan : row[x][1];
      frame.shade(y, x) = state == PixelState::Filled ? row[x][2] : nan;
    }
  }
  return frame;
}

}  // namespace vsil
