#pragma once
// The right-angle baseline (RA): front-to-back iso-surface slicing; the first hit along each
// ray is a line pixel where (1 - |∇f_n·V|)^k > ε (gradients by central differences). Slices
// record the first hit (hit_records.h FirstHitRecorder); the line test and shade run once per
// pixel at the end (rightangle.glsl in shaders/finish_hits.frag); with --fill tone, so does the
// tone shading of the hits (tone_fill.h).
#include <optional>

#include "slicing/hit_records.h"
#include "slicing/technique_table.h"
#include "slicing/tone_fill.h"

namespace vsil {

TechniqueInfo rightAngleTechniqueInfo();

class RightAngleTechnique : public Technique {
 public:
  ResolvedOptions resolve(const FrameContext& frame) override;
  BrickOccupancy occupancy(const FrameContext& frame) const override;
  void beginFrame(const FrameContext& frame) override;
  void drawSlice(const FrameContext& frame, const SliceContext& slice) override;
  void endFrame(const FrameContext& frame) override;
  // The first-hit record, as firsthit's; the last passes relay their own (relayScreenPass).
  std::vector<const gl::RenderTarget*> relayTargets(const FrameContext&) const override {
    return {&hits_.record()};
  }
  FrameBuffers readBack(const FrameContext& frame) override;

 private:
  FirstHitRecorder hits_;
  std::optional<gl::RenderTarget> finished_;  // RGBA32F (state, depth, shade, 0)
  gl::Program* finish_ = nullptr;
  ToneFill toneFill_;  // --fill tone
};

}  // namespace vsil
