#pragma once
// What the techniques that look for the iso-surface's first hit share (silhouette, rightangle,
// firsthit): a per-pixel record (shaders/hit_records.glsl: state, depth, first-hit eye
// distance, a value of the technique's own), pixels marked dead once no later slice can change
// them, and a finishing pass that shades the first hit once per pixel and settles the state.
#include <optional>
#include <string>
#include <vector>

#include "slicing/technique.h"
#include "slicing/technique_table.h"

namespace vsil {

// shaders/hit_records.glsl, to list after common.glsl in these techniques' programs.
inline const std::vector<std::string>& hitRecordSources() {
  static const std::vector<std::string> sources{"shaders/hit_records.glsl"};
  return sources;
}

// Dead pixels are marked every this many slices: often enough to skip most of them, rarely
// enough that the marking pass costs little.
constexpr int kMarkDeadInterval = 8;

// When a pixel is dead (mark_dead.frag), besides the slices being past its ray's exit from
// occupied space.
enum class DeadRule {
  OwnRecord,         // its record is final (rightangle, firsthit)
  NeighbourRecords,  // its record and its 8 neighbours' are final (silhouette's contour test
                     // reads them)
  Opacity,           // its accumulated opacity (the record's alpha) reached `deadOpacity`
                     // (compositing.h: early ray termination)
};

// Writes depth 1 through `depthOnly` (a framebuffer with only the technique's depth buffer)
// at the pixels of this slice's polygon that mark_dead.frag keeps, reading the records in
// `record`; slice passes testing GREATER then skip them.
void markDeadPixels(const FrameContext& frame, const SliceContext& slice,
                    const gl::EmptyFramebuffer& depthOnly, const gl::RenderTarget& record,
                    DeadRule rule, float deadOpacity = 1.0f);

// Records each pixel's first iso-surface hit, for the techniques that need no more of a ray
// (rightangle, firsthit, demip's second sweep), in one of three pipelines (technique_table.h
// SlicingPipeline) that leave the same records. Fast: one pass per slice
// (shaders/first_hit.frag) keeps the first hit by blending, skips empty space in front and,
// every kMarkDeadInterval slices, pixels that have their hit. Paper: the same pass over every
// pixel of each slice polygon. Tiles: one compute dispatch after the slices (tile_march.h,
// shaders/first_hit_march.comp).
class FirstHitRecorder {
 public:
  // Instead of the iso value, a threshold per pixel: DEMIP's second sweep looks for the first
  // sample within `materialEps` of the pixel's maximum (an R32F texture of the frame's size).
  // Passes per slice only (Fast or Paper).
  struct MaterialThreshold {
    GLuint maximumTexture = 0;
    float materialEps = 0.0f;
  };

  // Targets for the frame's size, the program and its threshold (the iso value, or `material`);
  // for the passes per slice the record cleared and the depth where rays enter occupied bricks
  // written.
  void beginFrame(const FrameContext& frame, SlicingPipeline pipeline = SlicingPipeline::Fast,
                  std::optional<MaterialThreshold> material = std::nullopt);
  void drawSlice(const FrameContext& frame, const SliceContext& slice);
  // After the last slice: the march (tiles), or nothing.
  void endSlices(const FrameContext& frame);
  // RGBA32F (STATE_FILLED, depth, first-hit eye distance, 1) at hits, 0 elsewhere.
  const gl::RenderTarget& record() const { return targets_->record; }

 private:
  struct Targets {
    gl::RenderTarget record;
    gl::EmptyFramebuffer depthOnly;  // record's depth buffer alone, for marking dead pixels
  };
  std::optional<Targets> targets_;
  SlicingPipeline pipeline_ = SlicingPipeline::Fast;
  gl::Program* slicePass_ = nullptr;
  gl::Program* march_ = nullptr;
  GLuint maximumTexture_ = 0;  // bound for the slice pass when the threshold is per pixel
};

// The last pass of a frame (shaders/finish_hits.frag): shades the first hit recorded in
// `record` and writes (state, depth, shade, 0) into `output`. `shared` holds the technique's
// GLSL defining finishState(); the caller sets that function's uniforms.
gl::Program& finishProgram(const FrameContext& frame, const std::vector<std::string>& shared);
void finishRecords(const FrameContext& frame, gl::Program& finish, const gl::RenderTarget& record,
                   const gl::RenderTarget& output);

// Splits an RGBA32F (state, depth, shade, 0) image into FrameBuffers: depth NaN where EMPTY,
// shade NaN where not FILLED.
FrameBuffers frameFromStateImage(const cv::Mat& stateDepthShade);

}  // namespace vsil
