#pragma once
// Nagy–Klein one-pixel silhouettes (OPS). Per slice a footprint pass (alpha test), the contour
// of the footprint (8-neighbourhood) and the decision table combining it with the intermediate
// record; one extra empty slice after the last turns contours at the back into silhouettes.
// Two pipelines give the same pixels (RenderSettings::silhouettePipeline):
//  Paper: three passes, the intermediate record in ping-pong targets, as the paper draws it.
//  Fast:  footprint, then contour + decision fused into one pass that updates the record in
//         place with image load/store, skipping pixels that are already final.
#include <array>
#include <optional>

#include "slicing/technique.h"

namespace vsil {

class SilhouetteTechnique : public Technique {
 public:
  void beginFrame(const FrameContext& frame) override;
  void drawSlice(const FrameContext& frame, const SliceContext& slice) override;
  void endFrame(const FrameContext& frame) override;
  FrameBuffers readBack(const FrameContext& frame) override;

 private:
  void drawFootprint(const FrameContext& frame, const SliceContext& slice,
                     const PixelRect& clearBounds);
  void decidePaper(const FrameContext& frame, const Slice* slice, const PixelRect& bounds,
                   bool emptySlice);
  void decideInPlace(const FrameContext& frame, const Slice* slice, const PixelRect& bounds,
                     bool emptySlice);
  void decide(const FrameContext& frame, const Slice* slice, const PixelRect& bounds,
              bool emptySlice);

  struct Targets {
    gl::RenderTarget footprint;  // R8UI: 0 EMPTY, 1 FILLED
    gl::RenderTarget contour;    // R8UI: EMPTY, FILLED, CONTOUR (paper pipeline)
    // RGBA32F records (state, depth, first-hit eye distance, 0): ping-pong (paper) or [0] in
    // place (fast); the finished frame (state, depth, shade, 0) goes to the other one.
    std::array<gl::RenderTarget, 2> intermediate;
    gl::EmptyFramebuffer imageOnly;  // raster size for the in-place pass
  };
  struct Programs {
    gl::Program footprint{"slice.vert", "footprint.frag"};
    gl::Program contour{"screen.vert", "contour.frag"};
    gl::Program decision{"screen.vert", "decision.frag"};
    gl::Program decisionInPlace{"screen.vert", "decision_inplace.frag"};
    gl::Program finish{"screen.vert", "finish.frag"};
  };
  std::optional<Targets> targets_;
  std::optional<Programs> programs_;
  SilhouettePipeline pipeline_ = SilhouettePipeline::Fast;
  int current_ = 0;  // the intermediate target holding the latest record
  double previousSliceDepth_ = 0;
};

}  // namespace vsil
