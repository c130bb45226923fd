#include "slicing/techniques/silhouette/silhouette_technique.h"

#include <cmath>
#include <limits>

#include "core/error.h"
#include "slicing/gl_state.h"
#include "slicing/hit_records.h"
#include "slicing/texture_units.h"
#include "slicing/tile_march.h"
#include "slicing/tone_fill.h"

namespace vsil {
namespace {

// PixelRect (top-down pixels) to a GL scissor box (bottom-up).
void scissorTo(const PixelRect& rect, glm::ivec2 viewport) {
  glEnable(GL_SCISSOR_TEST);
  glScissor(rect.x0, viewport.y - rect.y1, rect.x1 - rect.x0, rect.y1 - rect.y0);
}

constexpr GLuint kZeroU[4] = {0, 0, 0, 0};
constexpr GLfloat kZeroF[4] = {0, 0, 0, 0};

std::vector<std::string> sources() {
  return {"shaders/hit_records.glsl", "techniques/silhouette/silhouette.glsl"};
}

// The tiles pipeline's workgroup (march.comp): a column of the tile per invocation, one apron
// column on each side; 30 rows and their two apron rows fill a column's 32-bit mask. As many
// slices per dispatch as one uniform block holds (1024 on llvmpipe, so one dispatch per frame
// for the nk3 datasets): a dispatch boundary costs a barrier and a reload of the records.
// Measured (nk3 on bonsai and neghip, 256² and 512², on a loaded 2-core machine; the table is
// in the commit message that wrote this): tiles of 14x30, 62x30 and 30x14 were within the
// noise of this shape, none consistently ahead; 64 slices per dispatch (7 dispatches for
// bonsai's 427 slices) was slower on bonsai for this march and the first-hit one.
constexpr MarchShape kMarchShape{{32, 1}, {30, 30}};

// Cleared coverage: above any slice index and depth, so that MIN blending keeps the first.
constexpr float kNoCoverage = 1e30f;

// One pixel's run from its fast-pipeline record (silhouette.glsl: state, hit depth, hit eye
// distance, latest CONTOUR depth; SLAB_RUN keeps a detected silhouette's hit), the slices its
// owned samples span (coverage.frag) and the shade at its hit (finish_hits.frag).
PairPixel pairPixel(const float* record, const float* coverage, float shade) {
  PairPixel pixel;
  // No owned sample inside the volume: a run without samples. (Samples outside the volume are
  // EMPTY and come only before or after the ray's samples inside, which convex slab pieces draw
  // on consecutive slices: combineInZOrder finds them as gaps between the runs' slices.)
  if (coverage[0] >= kNoCoverage) return pixel;
  pixel.first = std::int32_t(PixelState::Empty);
  pixel.firstSlice = std::int32_t(coverage[0]);
  pixel.lastSlice = std::int32_t(-coverage[1]);
  const float firstDepth = coverage[2], lastDepth = -coverage[3];
  pixel.last = lastDepth;
  const auto state = PixelState(std::uint8_t(record[0] + 0.5f));
  if (state == PixelState::Empty) return pixel;
  pixel.hit = record[1];
  pixel.eyeDistance = record[2];
  pixel.shade = shade;
  pixel.t = std::int32_t(state);
  if (state == PixelState::Contour && record[3] != lastDepth) {
    // Detection the fast pipeline applies lazily (decision_inplace.frag): an EMPTY sample
    // followed the latest contour inside this run.
    pixel.t = std::int32_t(PixelState::Silhouette);
  }
  if (PixelState(pixel.t) == PixelState::Silhouette) pixel.detectPrev = record[3];
  // The first sample is the hit or EMPTY. A hit there was FILLED when the run ends FILLED (a
  // CONTOUR first sample that turned FILLED combines alike: the state FILLED, the front's
  // hit), else CONTOUR (FILLED is final).
  if (pixel.hit == firstDepth) {
    pixel.first =
        std::int32_t(state == PixelState::Filled ? PixelState::Filled : PixelState::Contour);
  }
  return pixel;
}

}  // namespace

TechniqueInfo silhouetteTechniqueInfo() {
  TechniqueInfo info{"silhouette",
                     "Nagy–Klein one-pixel iso-surface silhouettes (OPS), broadened to --width",
                     withToneFillOptions({isoOption(), pipelineOption(SlicingPipeline::Tiles)}),
                     FrameOutputs{.state = true, .color = false, .depth = true},
                     [] { return std::make_unique<SilhouetteTechnique>(); },
                     /*usesGradients=*/false,
                     /*checkValues=*/checkToneFillValues,
                     /*needsOneTexture=*/tilesNeedOneTexture};
  info.slabRunsFastPipeline = true;  // its paper pipeline too (technique_table.h)
  // The contour test reads the 8 neighbours' footprints on the slice (one pixel's footprint
  // along z), plus one voxel for trilinear filtering.
  info.slabGhostVoxels = [](const OptionReader&, const View& view, glm::ivec3 dims) {
    return int(std::ceil(pixelFootprintVoxelsZ(view, dims))) + 1;
  };
  return info;
}

ResolvedOptions SilhouetteTechnique::resolve(const FrameContext& frame) {
  ResolvedOptions resolved;
  resolved.details = toneFill_.resolve(frame);
  return resolved;
}

BrickOccupancy SilhouetteTechnique::occupancy(const FrameContext& frame) const {
  return reachesIso(float(frame.options->number("iso")));
}

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
                gl::EmptyFramebuffer(size, depth),
                std::nullopt});
  }
  // A slab's options say fast, whatever --pipeline said (technique_table.h optionsForSlab).
  pipeline_ = pipelineOf(*frame.options);
  slabCombined_ = false;
  const float iso = float(frame.options->number("iso"));
  programs_.finish = &finishProgram(frame, {"techniques/silhouette/silhouette.glsl"});
  if (pipeline_ == SlicingPipeline::Tiles) {
    requireOneBrick(frame, "--pipeline tiles", "use --pipeline fast or paper (the same pixels)");
    // The march writes every pixel's record once: nothing to clear, no depth buffer.
    programs_.march =
        &marchProgram(frame, sources(), "techniques/silhouette/march.comp", kMarchShape);
    programs_.march->use();
    programs_.march->set("isoValue", iso);
    current_ = 0;
    return;
  }
  const std::vector<std::string> variant = pipeline_ == SlicingPipeline::Paper
                                               ? std::vector<std::string>{"PAPER_PIPELINE"}
                                               : std::vector<std::string>{};
  // Only the programs this pipeline draws with: each costs a compile on a cold start.
  gl::ProgramCache& cache = *frame.programs;
  programs_.footprint =
      &cache.get(gl::slicePassProgram(sources(), "techniques/silhouette/footprint.frag", variant));
  if (pipeline_ == SlicingPipeline::Paper) {
    programs_.contour =
        &cache.get(gl::screenPassProgram(sources(), "techniques/silhouette/contour.frag", variant));
    programs_.decision = &cache.get(
        gl::screenPassProgram(sources(), "techniques/silhouette/decision.frag", variant));
    programs_.emptySliceDecision = &cache.get(gl::screenPassProgram(
        sources(), "techniques/silhouette/decision.frag", {"PAPER_PIPELINE", "EMPTY_SLICE"}));
  } else {
    std::vector<std::string> decisionVariant = variant;
    if (frame.slab) decisionVariant.emplace_back("SLAB_RUN");
    programs_.decisionInPlace = &cache.get(gl::slicePassProgram(
        sources(), "techniques/silhouette/decision_inplace.frag", decisionVariant));
  }
  if (frame.slab) {
    programs_.coverage =
        &cache.get(gl::slicePassProgram(sources(), "techniques/silhouette/coverage.frag", {}));
    if (!targets_->coverage) targets_->coverage.emplace(size, GL_RGBA32F);
    targets_->coverage->bindForDrawing();
    const GLfloat none[4] = {kNoCoverage, kNoCoverage, kNoCoverage, kNoCoverage};
    VSIL_GL(glClearBufferfv(GL_COLOR, 0, none));
  }
  programs_.footprint->use();
  programs_.footprint->set("isoValue", iso);

  glDisable(GL_SCISSOR_TEST);
  for (const gl::RenderTarget* target : {&targets_->footprint, &targets_->contour}) {
    target->bindForDrawing();
    VSIL_GL(glClearBufferuiv(GL_COLOR, 0, kZeroU));
  }
  // The fast pipeline's footprint pass tests GREATER against this depth: pixels in front of
  // the first occupied brick, and dead pixels later, are skipped.
  targets_->footprint.bindForDrawing();
  frame.emptySpace->writeEntryDepth(glm::mat4(frame.view->clipFromVoxel()));
  for (const auto& target : targets_->records) {
    target.bindForDrawing();
    VSIL_GL(glClearBufferfv(GL_COLOR, 0, kZeroF));
  }
  current_ = 0;
}

void SilhouetteTechnique::drawSlice(const FrameContext& frame, const SliceContext& slice) {
  const glm::ivec2 viewport = frame.view->viewport;
  if (pipeline_ == SlicingPipeline::Tiles) return;  // endFrame marches every slice at once
  if (pipeline_ == SlicingPipeline::Fast) {
    if (slice.vertexCount == 0) return;
    // Tagged with this slice, the footprint needs no clearing (silhouette.glsl footprintTag).
    drawFootprint(frame, slice);
    // The decision reads the records the previous slice's decision stored. The barrier
    // comes after this footprint pass so that llvmpipe, which waits for all queued work at a
    // barrier, waits once per slice: the decision's read of the footprint then finds it done.
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
    decideInPlace(frame, slice);
    if (frame.slab) {
      targets_->coverage->bindForDrawing();
      programs_.coverage->use();
      gl::Blending keepFirstAndLast(GL_MIN, GL_ONE, GL_ONE);
      drawSlicePolygon(frame, slice);
    }
    if (slice.index % kMarkDeadInterval == kMarkDeadInterval - 1) {
      glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);  // marking reads this slice's records
      markDeadPixels(frame, slice, targets_->depthOnly, targets_->records[0],
                     DeadRule::NeighbourRecords);
    }
    return;
  }
  // Pixels whose record may change here: this polygon (c != EMPTY) and the previous one
  // (contours there meet c = EMPTY); the ping-pong targets must also agree outside the pass,
  // which needs the slice before that too. One pixel more for the contour's neighbourhood.
  const PixelRect bounds = slice.recentUnion(3, 1, viewport);
  if (bounds.empty()) return;
  // Everything the next passes read outside this polygon must be EMPTY.
  scissorTo(bounds, viewport);
  targets_->footprint.bindForDrawing();
  VSIL_GL(glClearBufferuiv(GL_COLOR, 0, kZeroU));
  if (slice.vertexCount > 0) drawFootprint(frame, slice);
  contourPaper(frame, bounds);
  decidePaper(frame, /*emptySlice=*/false, bounds);
}

void SilhouetteTechnique::drawFootprint(const FrameContext& frame, const SliceContext& slice) {
  gl::Capability noScissor(GL_SCISSOR_TEST, false);
  targets_->footprint.bindForDrawing();
  programs_.footprint->use();
  if (pipeline_ == SlicingPipeline::Fast) {
    // Slices come in depth order: GREATER passes every pixel but dead ones (depth 1), early;
    // FILLED fragments (not discarded) leave this slice's depth for the decision pass.
    gl::DepthTest depthTest(GL_GREATER, /*write=*/true);
    drawSlicePolygon(frame, slice);
    // A slab's ghost pieces: the footprint the contour test reads beside the samples it owns
    // (the decision runs only over its own pieces).
    drawGhostPieces(frame, slice);
  } else {
    drawSlicePolygon(frame, slice);
  }
}

void SilhouetteTechnique::contourPaper(const FrameContext& frame, const PixelRect& bounds) {
  scissorTo(bounds, frame.view->viewport);
  targets_->contour.bindForDrawing();
  programs_.contour->use();
  gl::bindTexture(gl::TextureUnit::Footprint, GL_TEXTURE_2D, targets_->footprint.texture());
  drawScreen(frame);
}

void SilhouetteTechnique::decidePaper(const FrameContext& frame, bool emptySlice,
                                      const PixelRect& bounds) {
  scissorTo(bounds, frame.view->viewport);
  const int next = 1 - current_;
  targets_->records[std::size_t(next)].bindForDrawing();
  (emptySlice ? programs_.emptySliceDecision : programs_.decision)->use();
  gl::bindTexture(gl::TextureUnit::Contour, GL_TEXTURE_2D, targets_->contour.texture());
  gl::bindTexture(gl::TextureUnit::Record, GL_TEXTURE_2D,
                  targets_->records[std::size_t(current_)].texture());
  drawScreen(frame);
  current_ = next;
}

void SilhouetteTechnique::decideInPlace(const FrameContext& frame, const SliceContext& slice) {
  targets_->depthOnly.bindForDrawing();
  gl::DepthTest onlyFilled(GL_EQUAL, /*write=*/false);
  programs_.decisionInPlace->use();
  gl::bindImage(gl::ImageUnit::Record, targets_->records[0]);
  gl::bindTexture(gl::TextureUnit::Footprint, GL_TEXTURE_2D, targets_->footprint.texture());
  gl::bindTexture(gl::TextureUnit::Record, GL_TEXTURE_2D, targets_->records[0].texture());
  drawSlicePolygon(frame, slice);
}

void SilhouetteTechnique::combineSlabs(const FrameContext& frame, SlabRelay& relay) {
  if (toneFill_.active()) {
    throw UnavailableError(
        "--fill tone: not across MPI ranks yet (it shades every hit with the volume there); "
        "run one rank");
  }
  const glm::ivec2 size = frame.view->viewport;
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT |
                  GL_TEXTURE_UPDATE_BARRIER_BIT);
  // Each run's hit is shaded here, where its bricks are: the shade travels with the hit.
  targets_->records[1].bindForDrawing();
  VSIL_GL(glClearBufferfv(GL_COLOR, 0, kZeroF));
  finishRecords(frame, *programs_.finish, targets_->records[0], targets_->records[1]);
  const std::vector<float> records = targets_->records[0].readFloats();
  const std::vector<float> shaded = targets_->records[1].readFloats();
  const std::vector<float> coverage = targets_->coverage->readFloats();
  std::vector<PairPixel> pixels(std::size_t(size.x) * std::size_t(size.y));
  for (int row = 0; row < size.y; ++row) {
    // GL's rows run bottom-up; the view's pixels top-down.
    const double y = size.y - row - 0.5;
    for (int x = 0; x < size.x; ++x) {
      const std::size_t i = std::size_t(row) * std::size_t(size.x) + std::size_t(x);
      pixels[i] = pairPixel(&records[4 * i], &coverage[4 * i], shaded[4 * i + 2]);
      pixels[i].zDirection = rayZDirection(*frame.view, {x + 0.5, y});
    }
  }
  relay.pairReduce(pixels);
  // The whole ray's run meets the extra empty slice behind the volume (the paper's; the
  // single process's finish_hits.frag finishState): what is still CONTOUR becomes SILHOUETTE.
  std::vector<float> finished(pixels.size() * 4, 0.0f);
  for (std::size_t i = 0; i < pixels.size(); ++i) {
    composition::NkRun run = runOf(pixels[i]);
    const composition::NkSample emptySlice{PixelState::Empty, run.last};
    run = composition::combine(run, composition::foldNk({&emptySlice, 1}));
    finished[4 * i] = float(std::uint8_t(run.t));
    if (run.t == PixelState::Empty) continue;
    finished[4 * i + 1] = run.depth();
    finished[4 * i + 2] = pixels[i].shade;
  }
  targets_->records[1].writeFloats(finished);
  current_ = 1;
  slabCombined_ = true;
}

void SilhouetteTechnique::endFrame(const FrameContext& frame) {
  if (slabCombined_) return;
  if (pipeline_ == SlicingPipeline::Tiles) {
    runMarch(frame, *programs_.march, kMarchShape, targets_->records[0]);
    finishRecords(frame, *programs_.finish, targets_->records[0], targets_->records[1]);
    toneFill_.draw(frame, targets_->records[0]);
    current_ = 1;
    return;
  }
  if (pipeline_ == SlicingPipeline::Paper) {
    // The extra empty slice, over the whole image: contours at the back become silhouettes.
    decidePaper(frame, /*emptySlice=*/true, {0, 0, frame.view->viewport.x, frame.view->viewport.y});
  }
  // (The fast pipeline's finishing pass turns remaining contours into silhouettes itself; it
  // reads the records the last decision stored.)
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
  finishRecords(frame, *programs_.finish, targets_->records[std::size_t(current_)],
                targets_->records[std::size_t(1 - current_)]);
  toneFill_.draw(frame, targets_->records[std::size_t(current_)]);
  current_ = 1 - current_;
}

FrameBuffers SilhouetteTechnique::readBack(const FrameContext&) {
  FrameBuffers frame =
      frameFromStateImage(readTargetFlipped(targets_->records[std::size_t(current_)], 4));
  toneFill_.readBack(frame);
  return frame;
}

}  // namespace vsil
