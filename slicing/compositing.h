#pragma once
// Front-to-back compositing of view-aligned slices, shared by the techniques that accumulate
// colour (illustrate; mip's DVR composite and semantic next). The target is RGBA32F holding
// premultiplied colour and accumulated opacity: the slice pass writes (c·α, α) per pixel and the
// blending (ONE_MINUS_DST_ALPHA, ONE) adds it behind what is there, dst += (1 − dst.α)·src.
// Opacities are per voxel; shaders/compositing.glsl corrects them for the slice distance,
// α = 1 − (1 − o)^(Δ/Δ₀) with Δ₀ one voxel along the view (SlicePlan::stepVoxels).
//
// What no sample can change is skipped before the slice shader runs, as for the first-hit
// techniques: the depth buffer starts with where rays enter occupied bricks (empty_space.h) and
// the slice passes test GREATER; every kMarkDeadInterval slices, pixels past their ray's exit from
// occupied space and, with early ray termination (RenderSettings::earlyRayTermination), pixels
// whose opacity reached 1 − 1/255 get depth 1 (mark_dead.frag, DeadRule::Opacity). What the
// retired pixels would still have received is at most 1/255 of a colour in [0, 1].
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "slicing/technique.h"
#include "slicing/technique_table.h"

namespace vsil {

// The opacity from which a pixel takes no more samples.
inline constexpr float kTerminationOpacity = 1.0f - 1.0f / 255.0f;

class FrontToBackCompositor {
 public:
  // Targets for the frame's size; for the slice passes (drawSlice) cleared to transparent with
  // the entry depths written, for the tiles pipeline (march) as they are: the march writes every
  // pixel. Paper: drawSlice draws every pixel of each slice polygon (no skipping, no early ray
  // termination).
  void beginFrame(const FrameContext& frame, SlicingPipeline pipeline = SlicingPipeline::Fast);
  SlicingPipeline pipeline() const { return pipeline_; }  // beginFrame's
  // The tiles pipeline's program: marchProgram (tile_march.h) over `shared` and `computeFile`
  // in the compositor's march shape, MARK_DEAD_INTERVAL #defined besides `defines`.
  static gl::Program& marchProgram(const FrameContext& frame,
                                   const std::vector<std::string>& shared,
                                   const std::string& computeFile,
                                   std::vector<std::string> defines);
  // The tiles pipeline instead of drawSlice: `program` (from marchProgram, its uniforms set)
  // composites every pixel's samples in one march into the target, retiring pixels where
  // drawSlice's marks would.
  void march(const FrameContext& frame, gl::Program& program);
  // Draws the slice's polygon with `program` (in use, its uniforms set) blended behind what is
  // there, skipping empty space and retired pixels; marks newly retired ones every
  // kMarkDeadInterval slices. `auxiliaryBricks`: per-brick textures bound to
  // TextureUnit::Auxiliary0 with each piece (drawSlicePolygon).
  void drawSlice(const FrameContext& frame, const SliceContext& slice, gl::Program& program,
                 const std::vector<gl::TextureName>* auxiliaryBricks = nullptr);
  const gl::RenderTarget& target() const { return targets_->color; }
  // Premultiplied RGBA in [0, 1], rows top-down.
  cv::Mat4f readBack() const;

  // Δ/Δ₀ for compositing.glsl's `opacityExponent`.
  static float opacityExponent(const FrameContext& frame);

 private:
  struct Targets {
    gl::RenderTarget color;          // RGBA32F with the depth-stencil buffer the passes test
    gl::EmptyFramebuffer depthOnly;  // that depth buffer alone, for marking dead pixels
  };
  std::optional<Targets> targets_;
  float deadOpacity_ = kTerminationOpacity;
  SlicingPipeline pipeline_ = SlicingPipeline::Fast;
};

// The #define that puts each pixel's samples at whole steps from half a step past its ray's
// entry into the volume's box (common.glsl BOX_ALIGNED_SAMPLING; the technique's info sets
// samplesOffPlanes). On the planes, the first sample past a box face lies 0 to 1 step inside,
// varying along the face, which draws a rope along the box's edges wherever the box is the
// visible surface.
inline constexpr const char* kBoxAlignedSampling = "BOX_ALIGNED_SAMPLING";

// "shaders/compositing.glsl", to list before a compositing technique's own sources.
inline constexpr const char* kCompositingSource = "shaders/compositing.glsl";

}  // namespace vsil
