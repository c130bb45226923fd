#pragma once
// Nagy–Klein one-pixel silhouettes (OPS): per slice a footprint pass (alpha test), a contour
// pass (8-neighbourhood) and a decision pass (the decision table) into ping-pong intermediate
// targets; one extra empty slice after the last turns contours at the back into silhouettes.
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
  void decide(const FrameContext& frame, const Slice* slice, double previousDepth,
              const PixelRect& bounds, bool emptySlice);

  struct Targets {
    gl::RenderTarget footprint;  // R8UI: 0 EMPTY, 1 FILLED
    gl::RenderTarget contour;    // R8UI: EMPTY, FILLED, CONTOUR
    std::array<gl::RenderTarget, 2> intermediate;  // RGBA32F (state, depth, shade, 0)
  };
  struct Programs {
    gl::Program footprint{"slice.vert", "footprint.frag"};
    gl::Program contour{"screen.vert", "contour.frag"};
    gl::Program decision{"screen.vert", "decision.frag"};
  };
  std::optional<Targets> targets_;
  std::optional<Programs> programs_;
  int current_ = 0;  // the intermediate target holding the latest result
  double previousSliceDepth_ = 0;
};

}  // namespace vsil
