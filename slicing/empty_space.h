#pragma once
// Empty-space skipping, shared by every technique.
//
// The volume is cut into bricks of kBrickSize³ voxels; each brick keeps the range [min, max] of
// the samples that trilinear filtering can reach from any position inside it. A filtered sample
// is a convex combination of its eight voxels, so it lies in that range. The technique decides
// from the range whether a brick may hold anything it shows (Technique::occupancy: a brick whose
// maximum is below the iso value holds no FILLED sample; one over whose range the transfer
// function is transparent adds nothing). Before the slices, a technique draws the front faces of
// the occupied bricks into its depth buffer with depth test LESS: what remains is,
// per pixel, the depth where the view ray first enters an occupied brick, and 1 where it never
// does. Slice passes that test GREATER against it then skip, before their shader runs, every
// pixel in front of the volume's content and every pixel whose ray misses it. The faces turned
// away from the eye give where each ray leaves occupied space for good; the passes that mark
// dead pixels (mark_dead.frag) mark those pixels too once the slices are past it. Compute
// passes, which have no depth test, read the entry depth from an image instead. Skipped
// pixels are exactly those whose samples stay below the iso value, so no output changes (the
// GL tests compare against a CPU reference that samples everything).
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "core/camera.h"
#include "core/volume.h"
#include "slicing/gl_objects.h"
#include "slicing/shader_program.h"

namespace vsil {

class BrickRanges {
 public:
  // 8: bonsai 256³ at 512² rendered fastest with it among 4, 8, 16 and 32 (commit message).
  static constexpr int kBrickSize = 8;

  explicit BrickRanges(const Volume& volume);

  // How many bricks cover a volume of `dims` voxels along each axis.
  static glm::ivec3 bricksCovering(glm::ivec3 dims) { return (dims + kBrickSize - 1) / kBrickSize; }

  glm::ivec3 bricks() const { return bricks_; }
  // The smallest and largest voxel a trilinear sample inside the brick can read.
  ValueRange range(glm::ivec3 brick) const;
  // The smallest and largest voxel of the volume (valueRange's, without another pass over the
  // samples: every voxel lies in a brick).
  ValueRange whole() const;
  // The brick's sample positions: [kB - 0.5, (k+1)B - 0.5] per axis, cut to the volume's box.
  glm::dvec3 regionLow(glm::ivec3 brick) const;
  glm::dvec3 regionHigh(glm::ivec3 brick) const;

 private:
  glm::ivec3 dims_{0};
  glm::ivec3 bricks_{0};
  std::vector<ValueRange> ranges_;  // x fastest
};

// Whether a brick may hold anything a technique shows, from its value range.
using BrickOccupancy = std::function<bool(ValueRange brick)>;

// The bricks (x fastest, as BrickRanges numbers them) that read a voxel set in `voxels` (`dims`
// voxels, x fastest): every sample position whose nearest or filtered voxels include one lies in
// such a brick. For Technique::alsoOccupied.
std::vector<bool> bricksReading(const std::vector<std::uint8_t>& voxels, glm::ivec3 dims);

// Triangles, in voxel coordinates, of the boundary faces of the occupied bricks: each occupied
// brick's region grown by kEntryMargin voxels (so that float rounding in rasterization never
// matters), and none that lies inside the next occupied brick (a ray crossing it is inside that
// brick already). Entry faces are turned towards the eye, exit faces away from it: the nearest
// entry face along a ray is where it first enters occupied space, the farthest exit face where
// it leaves it for good.
struct OccupiedFaces {
  std::vector<glm::vec3> entry;
  std::vector<glm::vec3> exit;
};
// `alsoOccupied` (empty, or one flag per brick) adds bricks whatever their value range
// (Technique::alsoOccupied).
OccupiedFaces occupiedFaces(const BrickRanges& ranges, const BrickOccupancy& occupied,
                            const View& view, const std::vector<bool>& alsoOccupied = {});
constexpr double kEntryMargin = 0.5;

// The GL side: per frame, the occupied bricks' entry faces (drawn into a technique's depth
// buffer) and the exit depth image, which marking passes (mark_dead.frag) read.
class EmptySpaceSkipping {
 public:
  EmptySpaceSkipping();
  // Uploads this frame's faces and draws the exit depth image; `enabled` false turns skipping
  // off (entry depth 0, exit depth 1 everywhere).
  void prepare(const BrickRanges& ranges, const BrickOccupancy& occupied, const View& view,
               bool enabled, const std::vector<bool>& alsoOccupied = {});
  // Into the bound framebuffer's depth-stencil buffer: stencil 0 and, per pixel, a depth no
  // greater than that of the first slice whose sample there may reach the iso value (1 where
  // none can). Colour buffers are left untouched.
  void writeEntryDepth(const glm::mat4& clipFromVoxel);
  // The same depth as an R32F image (entryDepthTexture), for passes without a depth test (the
  // tile march, tile_march.h). Draws it; the caller asks once per frame.
  void drawEntryDepthImage(const glm::mat4& clipFromVoxel);
  GLuint entryDepthTexture() const { return entryDepth_ ? entryDepth_->texture() : 0; }
  // R32F, per pixel the window depth beyond which the ray meets no occupied brick (0 where it
  // meets none at all).
  GLuint exitDepthTexture() const { return exitDepth_ ? exitDepth_->texture() : 0; }

 private:
  void drawFaces(gl::Program& program, const glm::mat4& clipFromVoxel, GLint first, GLsizei count);

  bool enabled_ = true;
  gl::Program entryProgram_;         // shaders/occupied_faces.{vert,frag}: depth only
  gl::Program depthAsColorProgram_;  // the window depth as colour (exit image, entry image)
  gl::BufferName buffer_;
  gl::VertexArrayName vertexArray_;
  GLsizei entryVertices_ = 0;  // entry faces first in the buffer, then exit faces
  GLsizei exitVertices_ = 0;
  std::optional<gl::RenderTarget> exitDepth_;
  std::optional<gl::RenderTarget> entryDepth_;  // made on the first drawEntryDepthImage
};

}  // namespace vsil
