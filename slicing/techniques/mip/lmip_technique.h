#pragma once
// lmip: local maximum intensity projection, the classic relative of DEMIP (Sato et al. 1998):
// each ray shows the first local maximum at or above --lmip-threshold, or its plain maximum
// where it never reaches the threshold, through mip's window or --tf. One sweep; the record is
// updated in place per slice (lmip_slice.frag); pixels whose maximum is found are retired (marked
// dead). No brick is skipped: any sample, however low, may end a run, so none can be left out.
// When the volume is one texture, a march (lmip_march.comp) does the same search instead, each
// ray stopping at its own maximum: the same record, the same bytes.
#include <optional>

#include "slicing/technique.h"
#include "slicing/technique_table.h"
#include "slicing/transfer_function_texture.h"

namespace vsil {

TechniqueInfo lmipTechniqueInfo();

class LmipTechnique : public Technique {
 public:
  ResolvedOptions resolve(const FrameContext& frame) override;  // background, threshold
  BrickOccupancy occupancy(const FrameContext& frame) const override;
  void beginFrame(const FrameContext& frame) override;
  void drawSlice(const FrameContext& frame, const SliceContext& slice) override;
  void endFrame(const FrameContext& frame) override;
  // The record lmip_slice.frag continues from (slabs have several bricks: never the march).
  std::vector<const gl::RenderTarget*> relayTargets(const FrameContext&) const override {
    return {&targets_->record};
  }
  FrameBuffers readBack(const FrameContext& frame) override;

 private:
  // Whether this frame marches (lmip_march.comp) instead of drawing passes per slice: the
  // volume is one texture (the record carries the search from one dispatch to the next).
  static bool marches(const FrameContext& frame);

  struct Targets {
    gl::RenderTarget record;         // RGBA32F (lmip_slice.frag) with the entry depth
    gl::EmptyFramebuffer depthOnly;  // the record's depth buffer alone, for retiring pixels
    gl::RenderTarget colour;         // RGBA32F, premultiplied
  };
  std::optional<Targets> targets_;
  gl::Program* slicePass_ = nullptr;
  std::optional<TransferFunctionTexture> transferTable_;  // --tf
};

}  // namespace vsil
