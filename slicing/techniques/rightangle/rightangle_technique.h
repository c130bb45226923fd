#pragma once
// The right-angle baseline (RA): front-to-back iso-surface slicing; the first hit along each
// ray is a line pixel where (1 - |∇f_n·V|)^k > ε (gradients by central differences). Slices
// record the first hit (rightangle.frag); the line test and shade run once per pixel at the
// end (rightangle.glsl in shaders/finish_hits.frag).
#include <optional>

#include "slicing/technique.h"
#include "slicing/technique_table.h"

namespace vsil {

TechniqueInfo rightAngleTechniqueInfo();

class RightAngleTechnique : public Technique {
 public:
  BrickOccupancy occupancy(const FrameContext& frame) const override;
  void beginFrame(const FrameContext& frame) override;
  void drawSlice(const FrameContext& frame, const SliceContext& slice) override;
  void endFrame(const FrameContext& frame) override;
  FrameBuffers readBack(const FrameContext& frame) override;

 private:
  struct Targets {
    gl::RenderTarget record;         // RGBA32F records (state, depth, first-hit eye distance, hit)
    gl::RenderTarget finished;       // RGBA32F (state, depth, shade, 0)
    gl::EmptyFramebuffer depthOnly;  // record's depth buffer alone, for marking dead pixels
  };
  std::optional<Targets> targets_;
  gl::Program* slicePass_ = nullptr;
  gl::Program* finish_ = nullptr;
};

}  // namespace vsil
