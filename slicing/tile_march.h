#pragma once
// The tile march (`--pipeline tiles`): instead of passes per slice, compute dispatches walk the
// slices themselves, one workgroup per screen tile: its invocations sample their pixels on slice
// after slice, front to back, at exactly the positions a slice pass samples, and keep the
// records in registers; a tile starts where its first ray enters occupied bricks and stops when
// none of its pixels can change (shaders/tile_march.glsl). What a technique does per slice is
// its compute shader: the silhouette technique's needs each pixel's 8-neighbourhood, sampled in
// a one-pixel apron around the tile (techniques/silhouette/march.comp); the first-hit march
// needs none (shaders/first_hit_march.comp). The records they leave are those of the
// techniques' slice pipelines, so the same finishing passes (hit_records.h) serve both.
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "slicing/technique.h"

namespace vsil {

// How a march covers the screen and the slices.
struct MarchShape {
  glm::ivec2 group{16, 16};  // invocations per workgroup (the shader lays them over its tile)
  glm::ivec2 tile{16, 16};   // the pixels whose records a workgroup writes
  // Slices per dispatch; at most FrameUniforms::slicesPerRange() (what one uniform block holds).
  // Fewer would only add dispatch boundaries (a barrier, the records stored and reloaded).
  int slicesPerDispatch = 1 << 30;
};

// The march's program: common.glsl, `shared`, shaders/tile_march.glsl, then `computeFile`, built
// for `shape` and the frame's slice layout, with the caller's own `defines`.
gl::Program& marchProgram(const FrameContext& frame, const std::vector<std::string>& shared,
                          const std::string& computeFile, const MarchShape& shape,
                          std::vector<std::string> defines = {});

// Runs a march over the whole viewport: draws the entry depth image, binds the entry and exit
// depths and `record` (image unit Record), and dispatches one workgroup per tile for each range
// of slices, the records made visible to the next dispatch and, after the last, to texture
// fetches. The caller has set the program's own uniforms (e.g. isoValue).
void runMarch(const FrameContext& frame, gl::Program& program, const MarchShape& shape,
              const gl::RenderTarget& record);

}  // namespace vsil
