#pragma once
// A technique is one paper's method expressed as passes over the shared slicing loop:
// the Renderer walks the slices front to back and calls drawSlice for each; the technique owns
// its render targets and programs. New techniques (illustrate, mip, semantic) plug in here.
#include <array>
#include <memory>
#include <string>

#include "core/frame.h"
#include "slicing/empty_space.h"
#include "slicing/gl_objects.h"
#include "slicing/renderer.h"
#include "slicing/slicer.h"

namespace vsil {

// What every pass of a frame shares. Owned by the Renderer.
struct FrameContext {
  const RenderSettings* settings = nullptr;
  const View* view = nullptr;
  const SlicePlan* plan = nullptr;
  glm::ivec3 dims{0};
  glm::dvec3 spacing{1.0};
  GLuint volumeTexture = 0;      // GL_TEXTURE_3D, R16F or R32F, data units, linear filtering
  GLuint sliceVertexArray = 0;   // all slice polygons, slice k at [firstVertex, +vertexCount)
  GLuint screenVertexArray = 0;  // empty VAO for the full-screen triangle (gl_VertexID)
  // Writes the depth where rays first enter occupied bricks into the bound depth buffer
  // (empty_space.h); slice passes testing GREATER against it skip empty space.
  EmptySpaceSkipping* emptySpace = nullptr;
};

struct SliceContext {
  int index = 0;
  const Slice* slice = nullptr;
  GLint firstVertex = 0;
  GLsizei vertexCount = 0;  // 0 when the plane misses the box
  // Pixels the polygons of this slice ([0]), the previous ([1]) and the one before ([2]) may
  // cover; empty where there is no such slice.
  std::array<PixelRect, 3> recentBounds;

  // The union of the bounds of the last `count` slices (1 to 3), grown by `margin` pixels.
  PixelRect recentUnion(int count, int margin, glm::ivec2 viewport) const;
};

class Technique {
 public:
  virtual ~Technique() = default;
  virtual void beginFrame(const FrameContext& frame) = 0;
  virtual void drawSlice(const FrameContext& frame, const SliceContext& slice) = 0;
  // GPU work after the last slice (e.g. the extra empty slice); the Renderer then calls glFinish.
  virtual void endFrame(const FrameContext& frame) = 0;
  virtual FrameBuffers readBack(const FrameContext& frame) = 0;
};

// "silhouette" or "rightangle"; throws InputError listing the names for anything else.
std::unique_ptr<Technique> makeTechnique(const std::string& name);

// Uniforms every slice shader reads (common.glsl): the volume, the camera and this slice.
void setSliceUniforms(gl::Program& program, const FrameContext& frame, const Slice* slice);

// Dead pixels are marked every this many slices: often enough to skip most of them, rarely
// enough that the marking pass costs little.
constexpr int kMarkDeadInterval = 8;

// Writes depth 1 through `depthOnly` (a framebuffer with only the technique's depth buffer)
// at the pixels of this slice's polygon that `markDead` (mark_dead.frag) keeps, reading the
// records in `record`; slice passes testing GREATER then skip them.
void markDeadPixels(gl::Program& markDead, const FrameContext& frame, const SliceContext& slice,
                    const gl::EmptyFramebuffer& depthOnly, const gl::RenderTarget& record);

// The last pass of a frame: shades the first hit recorded in `record` (state, depth, first-hit
// eye distance, ...; common.glsl) and writes (state, depth, shade, 0) into `output` (finish.frag).
void finishRecords(gl::Program& finish, const FrameContext& frame, const gl::RenderTarget& record,
                   const gl::RenderTarget& output);

// GL texture rows run bottom-up; FrameBuffers rows top-down. Reads the target's colour
// attachment as floats with `channels` channels (1 or 4) and flips it.
cv::Mat readTargetFlipped(const gl::RenderTarget& target, int channels);

// Splits an RGBA32F (state, depth, shade, 0) image into FrameBuffers: depth NaN where EMPTY,
// shade NaN where not FILLED.
FrameBuffers frameFromStateImage(const cv::Mat& stateDepthShade);

}  // namespace vsil
