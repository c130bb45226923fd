#pragma once
// mip and demip (Díaz & Vázquez, Depth-Enhanced Maximum Intensity Projection, VG 2010).
// mip: one sweep, MAX blending keeps each pixel's maximum (max_sample.frag); a finishing pass
// maps it through the window (mip_finish.frag). demip: the same first sweep, then a second one
// that records, per pixel, the first sample within --material-eps of that maximum (the engine's
// first-hit pass with a per-pixel threshold, hit_records.h, so its dead-pixel marking stops each
// ray at its hit), and the finishing pass weights the grey by that sample's depth and tints it
// from the colour sphere (colour_sphere.h). With both weights 0, demip draws mip's bytes.
// When the volume is one texture and the frame's slices fit one march (tile_march.h), both
// instead run as one compute dispatch sampling the same positions (max_march.comp): the same
// bytes, and demip's search for the first hit covers about the last rise of --material-eps
// before it instead of the whole ray up to it.
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "slicing/hit_records.h"
#include "slicing/technique_table.h"
#include "slicing/techniques/mip/colour_sphere.h"
#include "slicing/transfer_function_texture.h"

namespace vsil {

TechniqueInfo mipTechniqueInfo();
TechniqueInfo demipTechniqueInfo();

class MipTechnique : public Technique {
 public:
  explicit MipTechnique(bool depthEnhanced) : depthEnhanced_(depthEnhanced) {}
  // demip: reads --sphere-map (a PNG's texels).
  ResolvedOptions resolve(const FrameContext& frame) override;
  int sweepCount(const FrameContext& frame) const override;
  BrickOccupancy occupancy(const FrameContext& frame) const override;
  void beginFrame(const FrameContext& frame) override;
  void beginSweep(const FrameContext& frame) override;
  void drawSlice(const FrameContext& frame, const SliceContext& slice) override;
  void endFrame(const FrameContext& frame) override;
  FrameBuffers readBack(const FrameContext& frame) override;
  // mip: the maxima of every slab (Composition::MaxReduce).
  void combineSlabs(const FrameContext& frame, SlabRelay& relay) override;
  // demip (Composition::Relay): the first sweep's maxima, then (after the last slab's maxima
  // went to every rank: the second sweep's threshold is the whole ray's) the second's hits.
  std::vector<const gl::RenderTarget*> relayTargets(const FrameContext& frame) const override {
    if (frame.sweep == 1) return {&hits_.record()};
    return {&targets_->values};
  }

 private:
  void uploadSphereMap();  // colourSphere_'s image into sphereMapTexture_
  // Whether this frame marches (max_march.comp) instead of drawing passes per slice: the same
  // answer all frame long (the volume's bricks and the frame's slice count).
  static bool marches(const FrameContext& frame);
  void march(const FrameContext& frame);

  struct Targets {
    gl::RenderTarget colour;  // RGBA32F, premultiplied
    // The per-pixel values the frame's path writes: the march's record (RGBA32F,
    // max_march.comp), or the passes' maximum (R32F with the entry depth of empty-space
    // skipping).
    gl::RenderTarget values;
    bool marching;
  };
  bool depthEnhanced_;
  std::optional<Targets> targets_;
  FirstHitRecorder hits_;  // demip's second sweep
  gl::Program* maximumPass_ = nullptr;
  std::optional<TransferFunctionTexture> transferTable_;  // --tf
  ColourSphere colourSphere_;                             // demip's --sphere-map
  gl::TextureName sphereMapTexture_;                      // its image, when it has one
  bool sphereMapUploaded_ = false;                        // sphereMapTexture_ holds that image
};

// What mip, lmip and demip resolve alike: the black background (unless --background says
// otherwise) and the window used, for the metadata.
ResolvedOptions resolveMipFamily(const OptionReader& options);

// What a pixel's maximum holds where no slice sampled it (mip_finish.frag shows nothing there).
constexpr float kNoSample = -3.4e38f;

// The finishing pass of mip, lmip and demip (mip_finish.frag with `defines`) made current, with
// its window set, or with --tf its table uploaded into `transferTable` (made on first use) and
// bound, `values` bound where it reads the pixels' values and `colour` bound for drawing; the
// caller sets its variant's uniforms and draws the screen.
gl::Program& useMipFinish(const FrameContext& frame, std::vector<std::string> defines,
                          GLuint values, const gl::RenderTarget& colour,
                          std::optional<TransferFunctionTexture>& transferTable);
// The colour target as the frame's colour, and channel `depthChannel` of `record` as its depth
// where a pixel shows something and `hasDepth` holds for its record (NaN elsewhere); without
// `hasDepth` every shown pixel has its depth, and only that channel is read back. With
// `readDepth` false (RenderSettings::readDepth) the colour alone: no depth.
FrameBuffers colourWithDepth(const gl::RenderTarget& colour, const gl::RenderTarget& record,
                             int depthChannel,
                             const std::function<bool(const cv::Vec4f&)>& hasDepth, bool readDepth);

}  // namespace vsil
