#pragma once
// Nagy–Klein one-pixel silhouettes (OPS). Per slice a footprint pass (alpha test), the contour
// of the footprint (8-neighbourhood) and the decision table combining it with the record
// (silhouette.glsl); one extra empty slice after the last turns contours at the back into
// silhouettes. Three pipelines give the same pixels (--pipeline):
//  paper: three passes, the record in ping-pong targets, as the paper draws it.
//  fast:  the footprint pass writes this slice's depth at FILLED pixels; one pass fuses
//         contour and decision, runs only there (early depth test EQUAL) and updates the record
//         in place; detection (CONTOUR meeting an empty slice) is applied lazily
//         (decision_inplace.frag), the extra empty slice by the finishing pass. The depth
//         buffer starts with where rays enter occupied bricks (empty_space.h); every few
//         slices, pixels that can no longer matter get depth 1 (mark_dead.frag); the
//         footprint pass (depth test GREATER) skips both before sampling.
//  tiles: no passes per slice: one compute dispatch walks the slices, a workgroup per screen
//         tile with a one-pixel apron, footprint and contour in shared memory, the record in
//         registers (tile_march.h, march.comp); the finishing pass as in the fast pipeline.
//  The paper pipeline samples every pixel of every slice polygon (no empty-space skipping).
//  With --fill tone, the first hits are tone-shaded after the last slice (tone_fill.h).
#include <array>
#include <optional>

#include "slicing/technique.h"
#include "slicing/technique_table.h"
#include "slicing/tone_fill.h"

namespace vsil {

TechniqueInfo silhouetteTechniqueInfo();

class SilhouetteTechnique : public Technique {
 public:
  ResolvedOptions resolve(const FrameContext& frame) override;
  BrickOccupancy occupancy(const FrameContext& frame) const override;
  void beginFrame(const FrameContext& frame) override;
  void drawSlice(const FrameContext& frame, const SliceContext& slice) override;
  void endFrame(const FrameContext& frame) override;
  // A slab's run (the fast pipeline's record from EMPTY, with where its samples lie) reduced
  // with the other processes' in z order (SlabRelay::pairReduce); the process of the lowest z
  // then holds the whole frame's finished records and endFrame does nothing more.
  void combineSlabs(const FrameContext& frame, SlabRelay& relay) override;
  FrameBuffers readBack(const FrameContext& frame) override;

 private:
  struct Programs {
    gl::Program *footprint, *contour, *decision, *emptySliceDecision, *decisionInPlace, *finish,
        *march, *coverage;
  };
  void drawFootprint(const FrameContext& frame, const SliceContext& slice);
  // Paper pipeline: contour pass, then the decision pass into the other ping-pong target over
  // `bounds`; `emptySlice` means the extra empty slice (every c EMPTY).
  void contourPaper(const FrameContext& frame, const PixelRect& bounds);
  void decidePaper(const FrameContext& frame, bool emptySlice, const PixelRect& bounds);
  void decideInPlace(const FrameContext& frame, const SliceContext& slice);

  struct Targets {
    // R32UI: footprintTag() FILLED, else EMPTY. Fast pipeline: its depth holds the slice depth
    // of the latest FILLED sample (before any: where the ray enters occupied bricks), 1 at dead
    // pixels.
    gl::RenderTarget footprint;
    gl::RenderTarget contour;  // R8UI: EMPTY, FILLED, CONTOUR (paper pipeline)
    // RGBA32F records (silhouette.glsl): ping-pong (paper) or [0] updated in place (fast); the
    // finished frame (state, depth, shade, 0) goes to the other one.
    std::array<gl::RenderTarget, 2> records;
    gl::EmptyFramebuffer depthOnly;  // the footprint's depth, no colour: the in-place pass
    // A slab's (coverage.frag): the first and last slice of each pixel's owned samples.
    std::optional<gl::RenderTarget> coverage;
  };
  std::optional<Targets> targets_;
  Programs programs_{};
  SlicingPipeline pipeline_ = SlicingPipeline::Fast;
  int current_ = 0;            // the record target holding the latest record
  bool slabCombined_ = false;  // combineSlabs left the finished records in records[current_]
  ToneFill toneFill_;          // --fill tone
};

}  // namespace vsil
