#pragma once
// illustrate: Ebert–Rheingans volume illustration (IEEE Vis 2000). Front-to-back compositing of
// the slices (slicing/compositing.h: opacity corrected for the slice distance, early ray
// termination, empty-space skipping) with the paper's effects applied to every sample in the
// slice shader (composite.frag, the formulas in shaders/illustration.glsl): boundary and
// silhouette enhancement, oriented fading, sketch lines, distance colour blending, feature halos
// and tone shading, each switched on by --effects and shaped by --param with the paper's names,
// or loaded from a style (--style, a preset or a file; src/core/illustration.h).
//
// One program per set of effects (and transfer-function kind), built from #defines and cached:
// llvmpipe runs both sides of a branch, so an effect that is off must not be in the shader.
// Parameters are uniforms: changing one never recompiles.
#include <optional>
#include <string>
#include <vector>

#include "core/illustration.h"
#include "slicing/compositing.h"
#include "slicing/technique_table.h"
#include "slicing/techniques/illustrate/halo_mask.h"
#include "slicing/transfer_function_texture.h"

namespace vsil {

TechniqueInfo illustrateTechniqueInfo();

// --pipeline's default: tiles (march.comp, one compute dispatch composites every pixel's
// samples), 1.5–1.8× the frame rate of fast (README "The default pipeline"); over a volume in
// several bricks fast (technique_table.h optionsForBricks).
inline constexpr SlicingPipeline kIllustrateDefaultPipeline = SlicingPipeline::Tiles;

// The program variant for a set of effects and halo mode: its #defines.
std::vector<std::string> illustrateDefines(const Illustration& illustration, HaloMode haloMode);

// Halo taps: in the slice plane, 4 at half the radius along the view's x and y axes and 4 at
// the radius along the diagonals (8 directions); weights 1/d², summing to 1.
inline constexpr int kHaloTaps = 8;
struct HaloTap {
  glm::dvec2 offsetEye;  // unit direction in the view's plane (eye x, y) times the distance
  double distanceVoxels = 0;
  double weight = 0;
};
std::vector<HaloTap> haloTaps(double radiusVoxels);

// The data values the power opacity o_v = k_os·v^k_oe spans (no transfer function): v = 0 at
// the illustration's powerOpacityFrom (Otsu's threshold, clamped to the range), 1 at its
// powerOpacityTo (core/transfer_function.h classificationDomain).
ValueRange powerOpacityDomain(const Illustration& illustration, ValueRange range);
// Whether a voxel of value `value` is visible (opacity above 0) under the illustration's
// transfer function; conservative by one table entry, as the occupancy is.
std::function<bool(float)> visibleValues(const Illustration& illustration,
                                         const std::vector<glm::vec4>& table, ValueRange range);
// Whether no value in [lo, hi] is visible (the halo field's "nothing here", halo_mask.h).
std::function<bool(float, float)> transparentValues(const Illustration& illustration,
                                                    const std::vector<glm::vec4>& table,
                                                    ValueRange range);
// The value at or below which every sample is transparent (composite.frag leaves early there).
float transparentBelow(const Illustration& illustration, const std::vector<glm::vec4>& table,
                       ValueRange range);

class IllustrateTechnique : public Technique {
 public:
  ResolvedOptions resolve(const FrameContext& frame) override;
  BrickOccupancy occupancy(const FrameContext& frame) const override;
  std::vector<bool> alsoOccupied(const FrameContext& frame) const override;
  void beginFrame(const FrameContext& frame) override;
  void drawSlice(const FrameContext& frame, const SliceContext& slice) override;
  void endFrame(const FrameContext& frame) override;
  FrameBuffers readBack(const FrameContext& frame) override;
  // Across ranks (slab.h): the accumulated colour and the retired pixels travel in depth order.
  std::vector<const gl::RenderTarget*> relayTargets(const FrameContext&) const override {
    return {&compositor_.target()};
  }
  const gl::RenderTarget* relayDeadMarks(const FrameContext&) const override {
    return &compositor_.target();
  }

 private:
  void setUniforms(const FrameContext& frame);

  Illustration illustration_;
  HaloMode haloMode_ = HaloMode::Field;
  std::vector<glm::vec4> table_;  // the transfer function's table, when there is one
  std::optional<TransferFunctionTexture> transferTexture_;
  HaloMaskTexture haloMask_;
  FrontToBackCompositor compositor_;
  gl::Program* program_ = nullptr;
};

}  // namespace vsil
