#pragma once
// A technique is one paper's method expressed as passes over the shared slicing loop. The
// Renderer walks the slices front to back once per sweep (most techniques need one; DEMIP two)
// and calls drawSlice for each; the technique owns its render targets and takes its programs
// from the Renderer's cache. What a technique is called, which options it reads and what it
// returns is declared once in technique_table.h.
#include <array>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/color.h"
#include "core/frame.h"
#include "core/options.h"
#include "core/volume.h"
#include "slicing/empty_space.h"
#include "slicing/frame_uniforms.h"
#include "slicing/gl_objects.h"
#include "slicing/gradient_texture.h"
#include "slicing/renderer.h"
#include "slicing/shader_program.h"
#include "slicing/slab.h"
#include "slicing/slicer.h"
#include "slicing/volume_texture.h"

namespace vsil {

// What every pass of a frame shares. Owned by the Renderer.
struct FrameContext {
  const RenderSettings* settings = nullptr;
  const OptionReader* options = nullptr;  // the technique's options, defaults resolved
  const View* view = nullptr;
  const SlicePlan* plan = nullptr;
  glm::ivec3 dims{0};
  glm::dvec3 spacing{1.0};
  ValueRange valueRange;
  // The volume's bricked textures; with one brick, bound to TextureUnit::Volume (and its
  // BrickBlock) for the whole frame, else drawSlicePolygon binds each piece's brick.
  const VolumeTexture* volume = nullptr;
  GLuint sliceVertexArray = 0;   // all slice pieces, slice k's at [firstVertex, +vertexCount)
  GLuint screenVertexArray = 0;  // empty VAO for the full-screen triangle (gl_VertexID)
  // Writes the depth where rays first enter occupied bricks into the bound depth buffer
  // (empty_space.h); slice passes testing GREATER against it skip empty space.
  EmptySpaceSkipping* emptySpace = nullptr;
  gl::ProgramCache* programs = nullptr;
  const FrameUniforms* uniforms = nullptr;
  // The volume's gradient texture (gradient_texture.h), built on first use and kept for the
  // volume's lifetime: only techniques that ask pay for it.
  GradientTextureCache* gradients = nullptr;
  // Changes whenever the Renderer gets a new volume: techniques keying caches of their own on
  // the volume (illustrate's halo mask) compare it.
  int volumeGeneration = 0;
  // What the frame is composed over: RenderSettings::background, else what the technique's
  // resolve() chose, else white (distance colour blending's c_b).
  Rgba background = kDefaultBackground;
  int sweep = 0;  // which sweep over the slices is being drawn (0 .. sweepCount - 1)
  // Set when this process renders one slab of a volume split across processes (slab.h): the
  // slices then hold only the pieces of the bricks it owns.
  const SlabPart* slab = nullptr;
};

// A piece of a slice polygon (slicer.h slicePieces): its vertices in the slice vertex array
// and the brick it samples.
struct PieceDraw {
  GLint firstVertex = 0;
  GLsizei vertexCount = 0;
  std::size_t brick = 0;
};

struct SliceContext {
  int index = 0;
  const Slice* slice = nullptr;
  GLint firstVertex = 0;
  GLsizei vertexCount = 0;  // of all its pieces; 0 when the plane misses the box
  std::vector<PieceDraw> pieces;
  // A slab's pieces of the ghost bricks it holds but does not own (slab.h): drawn only where a
  // technique reads neighbouring pixels of the slice (silhouette's footprint), never counted in
  // vertexCount.
  std::vector<PieceDraw> ghostPieces;
  // Pixels the polygons of this slice ([0]), the previous ([1]) and the one before ([2]) may
  // cover; empty where there is no such slice.
  std::array<PixelRect, 3> recentBounds;

  // The union of the bounds of the last `count` slices (1 to 3), grown by `margin` pixels.
  PixelRect recentUnion(int count, int margin, glm::ivec2 viewport) const;
};

// What a technique made of its options before the frame (Technique::resolve).
struct ResolvedOptions {
  // The colour to compose over when the caller chose none (e.g. an illustration style's).
  std::optional<Rgba> background;
  // Added to RenderResult::options for the metadata (e.g. {"illustration": {...}}).
  nlohmann::json details = nlohmann::json::object();
};

class Technique {
 public:
  virtual ~Technique() = default;
  // First in every frame, before occupancy() and alsoOccupied(): reads the options and any files
  // they name (styles, transfer functions), throwing InputError for bad ones, and prepares what
  // those two answer from (illustrate's halo mask).
  virtual ResolvedOptions resolve(const FrameContext&) { return {}; }
  virtual int sweepCount(const FrameContext&) const { return 1; }
  // Which bricks may hold something this frame shows (empty_space.h); the others are skipped
  // without sampling, so the occupancy must refuse only bricks that cannot change a pixel.
  virtual BrickOccupancy occupancy(const FrameContext& frame) const = 0;
  // Bricks occupied whatever their value range (one flag per brick, bricksReading; empty:
  // none): for techniques whose samples read a neighbourhood (illustrate's halos add opacity
  // beside what the occupancy admits).
  virtual std::vector<bool> alsoOccupied(const FrameContext&) const { return {}; }
  virtual void beginFrame(const FrameContext& frame) = 0;
  virtual void beginSweep(const FrameContext&) {}
  virtual void drawSlice(const FrameContext& frame, const SliceContext& slice) = 0;
  // GPU work after the last sweep (e.g. the extra empty slice); the Renderer then calls glFinish.
  virtual void endFrame(const FrameContext& frame) = 0;
  virtual FrameBuffers readBack(const FrameContext& frame) = 0;
  // Slab rendering (slab.h): after this process's slices, before endFrame, combines its partial
  // frame with the other processes' by the technique's rule (TechniqueInfo::composition), so
  // that every process finishes the whole frame. Default: the technique cannot be split.
  virtual void combineSlabs(const FrameContext& frame, SlabRelay& relay);
  // Slab rendering by relay (Composition::Relay): the targets that hold this sweep's partial
  // frame (frame.sweep), received from the slab in front after beginSweep and sent on after the
  // slices. Only the colour and the depth-stencil buffer travel, so the technique must keep
  // everything a later slice reads there.
  virtual std::vector<const gl::RenderTarget*> relayTargets(const FrameContext&) const {
    return {};
  }
  // The target whose depth-stencil buffer holds the pixels retired by early ray termination
  // (compositing.h), relayed with relayTargets: a pixel the slab in front retired there took
  // its last sample in front (mark_dead.frag marks a slab's pixels only at slices whose sample
  // lies in the slab), so no later slab adds to it, as in one process. nullptr: none travels.
  virtual const gl::RenderTarget* relayDeadMarks(const FrameContext&) const { return nullptr; }
};

// The occupancy of techniques that look for the iso-surface: a brick may hold a FILLED sample
// when its maximum reaches the iso value. A small relative slack absorbs float rounding in the
// filter's weights (R32F volumes).
BrickOccupancy reachesIso(float iso);

// Draws the slice's polygon as its pieces, one per brick (it rasterizes every pixel whose
// centre lies in the box on this plane, and some around it, exactly once); the Renderer has
// bound the slice's uniform block before drawSlice. With more than one brick, binds each
// piece's volume texture, gradient texture (once built), BrickBlock and, where given, its
// texture of `auxiliaryBricks` (one per brick; TextureUnit::Auxiliary0).
void drawSlicePolygon(const FrameContext& frame, const SliceContext& slice,
                      const std::vector<gl::TextureName>* auxiliaryBricks = nullptr);
// The same for the slice's ghost pieces (a slab's, SliceContext::ghostPieces).
void drawGhostPieces(const FrameContext& frame, const SliceContext& slice);
// Throws InputError "<what> needs the volume in one texture ... (<hint>)" when the volume
// takes more than one brick: for the passes that cannot follow the bricks (compute marches,
// illustrate's halos).
void requireOneBrick(const FrameContext& frame, const std::string& what, const std::string& hint);

// One triangle over the viewport (screen passes; limit them with a scissor).
void drawScreen(const FrameContext& frame);
// drawScreen once per brick, with that brick's volume texture and BrickBlock bound (brick 0's
// again afterwards): for the screen passes after the last slice that sample the volume at a
// pixel's own point (finish_hits.frag, tone_fill.frag). Each pass must write only the pixels
// whose point its brick owns (common.glsl ownedByBrick), and those without a point only on the
// first brick (brickIsFirst), so that every pixel is written once, by the brick that holds its
// neighbourhood: the same bytes as one texture.
// A slab (frame.slab) draws only the bricks it owns, so that it writes only the pixels whose point
// lies in its slab: relayScreenPass then completes the frame.
void drawScreenPerBrick(const FrameContext& frame);
// A screen pass per brick into `targets` (`draw`, e.g. finishRecords) of a frame split into slabs
// (Composition::Relay): each rank in turn continues from the targets of the one in front and
// writes the pixels its bricks own, and the last rank's targets go to all; every pixel so holds
// what the brick owning its point wrote, as in one process. Without a slab, just draw().
void relayScreenPass(const FrameContext& frame, const std::vector<const gl::RenderTarget*>& targets,
                     const std::function<void()>& draw);

// GL texture rows run bottom-up; FrameBuffers rows top-down. Reads the target's colour
// attachment as floats with `channels` channels (1 or 4) and flips it.
cv::Mat readTargetFlipped(const gl::RenderTarget& target, int channels);
// The same for one channel (0 red … 3 alpha) of a float target: a quarter of the bytes.
cv::Mat1f readChannelFlipped(const gl::RenderTarget& target, int channel);

}  // namespace vsil
