#pragma once
// firsthit: the depth of the first iso-surface hit along each ray, as a grey image (near white,
// far black) and a depth image. The smallest complete technique: the engine's first-hit pass
// (hit_records.h) with its empty-space skipping and dead-pixel marking, and a colour output
// with depth. A template for new techniques, and a depth map for figures and studies.
#include "slicing/hit_records.h"
#include "slicing/technique_table.h"

namespace vsil {

TechniqueInfo firstHitTechniqueInfo();

class FirstHitTechnique : public Technique {
 public:
  BrickOccupancy occupancy(const FrameContext& frame) const override;
  // Over black by default, as a depth image is shown: its near surfaces are white, and over the
  // default white background they vanished (the engine from behind: 85 % of its pixels at 240
  // or above). --background still chooses.
  ResolvedOptions resolve(const FrameContext&) override {
    ResolvedOptions resolved;
    resolved.background = Rgba{0, 0, 0, 255};
    return resolved;
  }
  void beginFrame(const FrameContext& frame) override { hits_.beginFrame(frame); }
  void drawSlice(const FrameContext& frame, const SliceContext& slice) override {
    hits_.drawSlice(frame, slice);
  }
  void endFrame(const FrameContext& frame) override { hits_.endSlices(frame); }
  // The record: a later slab's first-hit pass keeps what it holds (blending keeps the first).
  std::vector<const gl::RenderTarget*> relayTargets(const FrameContext&) const override {
    return {&hits_.record()};
  }
  FrameBuffers readBack(const FrameContext& frame) override;

 private:
  FirstHitRecorder hits_;
};

}  // namespace vsil
