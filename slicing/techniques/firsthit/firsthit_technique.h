#pragma once
// firsthit: the depth of the first iso-surface hit along each ray, as a grey image (near white,
// far black) and a depth image. The smallest complete technique: one slice pass, the engine's
// empty-space skipping and dead-pixel marking, a colour output with depth. A template for new
// techniques, and a depth map for figures and studies.
#include <optional>

#include "slicing/technique.h"
#include "slicing/technique_table.h"

namespace vsil {

TechniqueInfo firstHitTechniqueInfo();

class FirstHitTechnique : public Technique {
 public:
  BrickOccupancy occupancy(const FrameContext& frame) const override;
  void beginFrame(const FrameContext& frame) override;
  void drawSlice(const FrameContext& frame, const SliceContext& slice) override;
  void endFrame(const FrameContext&) override {}
  FrameBuffers readBack(const FrameContext& frame) override;

 private:
  struct Targets {
    gl::RenderTarget record;         // RGBA32F (STATE_FILLED, depth, eye distance, 1) at hits
    gl::EmptyFramebuffer depthOnly;  // record's depth buffer alone, for marking dead pixels
  };
  std::optional<Targets> targets_;
  gl::Program* slicePass_ = nullptr;
};

}  // namespace vsil
