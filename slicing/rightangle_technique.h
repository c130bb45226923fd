#pragma once
// The right-angle baseline (RA): front-to-back iso-surface slicing; the first hit along each
// ray is a line pixel where (1 - |∇f_n·V|)^k > ε (gradients by central differences).
#include <optional>

#include "slicing/technique.h"

namespace vsil {

class RightAngleTechnique : public Technique {
 public:
  void beginFrame(const FrameContext& frame) override;
  void drawSlice(const FrameContext& frame, const SliceContext& slice) override;
  void endFrame(const FrameContext&) override {}
  FrameBuffers readBack(const FrameContext& frame) override;

 private:
  std::optional<gl::RenderTarget> target_;  // RGBA32F (state, depth, shade, 0) + depth buffer
  std::optional<gl::Program> program_;
};

// Splits an RGBA32F (state, depth, shade, 0) image into FrameBuffers: depth NaN where EMPTY,
// shade NaN where not FILLED.
FrameBuffers frameFromStateImage(const cv::Mat& stateDepthShade);

}  // namespace vsil
