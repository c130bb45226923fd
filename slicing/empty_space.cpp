#include "slicing/empty_space.h"

#include "slicing/gl_state.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <thread>

#include "core/limits.h"

namespace vsil {

namespace {

constexpr int kB = BrickRanges::kBrickSize;

// The range of no values, which unite widens to any other.
constexpr ValueRange kNoValues{std::numeric_limits<float>::infinity(),
                               -std::numeric_limits<float>::infinity()};
void unite(ValueRange& r, ValueRange other) {
  r.min = std::min(r.min, other.min);
  r.max = std::max(r.max, other.max);
}

// The voxels brick k reads along one axis: positions [kB - 0.5, (k+1)B - 0.5] filter voxels
// kB - 1 .. (k+1)B; one more on each side absorbs rounding of the sample position.
int firstVoxel(int brick) {
  return brick * kB - 2;
}
int lastVoxel(int brick) {
  return (brick + 1) * kB + 1;
}
// Those of them inside a volume `dim` voxels long.
std::pair<int, int> voxelRange(int brick, int dim) {
  return {std::max(0, firstVoxel(brick)), std::min(dim - 1, lastVoxel(brick))};
}

}  // namespace

BrickRanges::BrickRanges(const Volume& volume)
    : dims_(volume.dims), bricks_(bricksCovering(volume.dims)) {
  const glm::ivec3 d = dims_, b = bricks_;
  ranges_.assign(std::size_t(b.x) * b.y * b.z, kNoValues);
  // Separable, one z plane at a time, so that the working memory is two planes of ranges
  // (limits::renderVolumeBytes counts them), not a range per 8 voxels of the whole volume:
  // a plane's ranges along x per row, then over y, then united into the bricks that read it.
  // Each thread owns a run of brick layers and reads the planes they read (a few planes at
  // the seams twice), so the threads never write the same brick.
  const int threads = std::min(limits::workerThreads(), b.z);
  struct Planes {  // allocated here: a thread that fails to allocate would end the process
    std::vector<ValueRange> alongX, alongY;
  };
  std::vector<Planes> planes(std::size_t(threads),
                             {std::vector<ValueRange>(std::size_t(b.x) * d.y),
                              std::vector<ValueRange>(std::size_t(b.x) * b.y)});
  auto layers = [&](int thread) {
    const int bz0 = b.z * thread / threads, bz1 = b.z * (thread + 1) / threads;
    // Plain references, not a structured binding: clang before 16 cannot capture one in the
    // lambda below (C++20 allows it), and the fuzz build uses Debian's clang 14.
    std::vector<ValueRange>& alongX = planes[std::size_t(thread)].alongX;
    std::vector<ValueRange>& alongY = planes[std::size_t(thread)].alongY;
    volume.visit([&](auto samples) {
      for (int z = voxelRange(bz0, d.z).first; z <= voxelRange(bz1 - 1, d.z).second; ++z) {
        for (int y = 0; y < d.y; ++y) {
          const auto* row = &samples[volume.index(0, y, z)];
          for (int bx = 0; bx < b.x; ++bx) {
            const auto [x0, x1] = voxelRange(bx, d.x);
            const auto [lo, hi] = std::minmax_element(row + x0, row + x1 + 1);
            alongX[std::size_t(y) * b.x + bx] = {float(*lo), float(*hi)};
          }
        }
        std::fill(alongY.begin(), alongY.end(), kNoValues);
        for (int by = 0; by < b.y; ++by) {
          const auto [y0, y1] = voxelRange(by, d.y);
          for (int y = y0; y <= y1; ++y) {
            for (int bx = 0; bx < b.x; ++bx) {
              unite(alongY[std::size_t(by) * b.x + bx], alongX[std::size_t(y) * b.x + bx]);
            }
          }
        }
        for (int bz = bz0; bz < bz1; ++bz) {
          const auto [z0, z1] = voxelRange(bz, d.z);
          if (z < z0 || z > z1) continue;
          for (int i = 0; i < b.x * b.y; ++i) {
            unite(ranges_[std::size_t(bz) * b.x * b.y + std::size_t(i)], alongY[std::size_t(i)]);
          }
        }
      }
    });
  };
  std::vector<std::jthread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(layers, t);
  layers(0);
}

std::vector<bool> bricksReading(const std::vector<std::uint8_t>& voxels, glm::ivec3 dims) {
  const glm::ivec3 bricks = BrickRanges::bricksCovering(dims);
  std::vector<bool> reading(std::size_t(bricks.x) * bricks.y * bricks.z);
  auto holdsOne = [&](glm::ivec3 brick) {
    const auto [x0, x1] = voxelRange(brick.x, dims.x);
    const auto [y0, y1] = voxelRange(brick.y, dims.y);
    const auto [z0, z1] = voxelRange(brick.z, dims.z);
    for (int z = z0; z <= z1; ++z) {
      for (int y = y0; y <= y1; ++y) {
        const auto row = voxels.begin() + std::ptrdiff_t((std::size_t(z) * dims.y + y) * dims.x);
        if (std::any_of(row + x0, row + x1 + 1, [](std::uint8_t v) { return v != 0; })) return true;
      }
    }
    return false;
  };
  for (int bz = 0, i = 0; bz < bricks.z; ++bz) {
    for (int by = 0; by < bricks.y; ++by) {
      for (int bx = 0; bx < bricks.x; ++bx, ++i) reading[std::size_t(i)] = holdsOne({bx, by, bz});
    }
  }
  return reading;
}

ValueRange BrickRanges::range(glm::ivec3 brick) const {
  return ranges_[(std::size_t(brick.z) * bricks_.y + brick.y) * bricks_.x + brick.x];
}

ValueRange BrickRanges::whole() const {
  ValueRange all = kNoValues;
  for (const ValueRange& r : ranges_) unite(all, r);
  return all;
}

glm::dvec3 BrickRanges::regionLow(glm::ivec3 brick) const {
  return glm::dvec3(brick * kB) - 0.5;
}

glm::dvec3 BrickRanges::regionHigh(glm::ivec3 brick) const {
  return glm::min(glm::dvec3((brick + 1) * kB), glm::dvec3(dims_)) - 0.5;
}

OccupiedFaces occupiedFaces(const BrickRanges& ranges, const BrickOccupancy& occupied,
                            const View& view, const std::vector<bool>& alsoOccupied) {
  const glm::dmat4 voxelFromEye = glm::inverse(view.eyeFromVoxel);
  // Perspective: a face is turned to the eye when the eye lies beyond its plane; orthographic:
  // when the direction towards the eye points out of it.
  const glm::dvec3 eye(voxelFromEye * glm::dvec4(0, 0, 0, 1));
  const glm::dvec3 towardsEye(voxelFromEye * glm::dvec4(0, 0, 1, 0));
  const glm::ivec3 bricks = ranges.bricks();
  OccupiedFaces faces;
  // Asked once per brick: the occupancy may be costly (a transfer function's opacity over a range).
  std::vector<bool> occupiedBricks(std::size_t(bricks.x) * bricks.y * bricks.z);
  for (int bz = 0, i = 0; bz < bricks.z; ++bz) {
    for (int by = 0; by < bricks.y; ++by) {
      for (int bx = 0; bx < bricks.x; ++bx, ++i) {
        occupiedBricks[std::size_t(i)] = (!alsoOccupied.empty() && alsoOccupied[std::size_t(i)]) ||
                                         occupied(ranges.range({bx, by, bz}));
      }
    }
  }
  auto isOccupied = [&](glm::ivec3 b) {
    return glm::all(glm::greaterThanEqual(b, glm::ivec3(0))) &&
           glm::all(glm::lessThan(b, bricks)) &&
           occupiedBricks[(std::size_t(b.z) * bricks.y + b.y) * bricks.x + b.x];
  };
  for (int bz = 0; bz < bricks.z; ++bz) {
    for (int by = 0; by < bricks.y; ++by) {
      for (int bx = 0; bx < bricks.x; ++bx) {
        const glm::ivec3 brick(bx, by, bz);
        if (!isOccupied(brick)) continue;
        const glm::dvec3 lo = ranges.regionLow(brick) - kEntryMargin;
        const glm::dvec3 hi = ranges.regionHigh(brick) + kEntryMargin;
        for (int axis = 0; axis < 3; ++axis) {
          for (int side : {-1, 1}) {
            glm::ivec3 next = brick;
            next[axis] += side;
            if (isOccupied(next)) continue;
            const double plane = side > 0 ? hi[axis] : lo[axis];
            const double towards =
                view.orthographic ? side * towardsEye[axis] : side * (eye[axis] - plane);
            if (towards == 0) continue;  // seen edge-on: covers no pixel
            std::vector<glm::vec3>& triangles = towards > 0 ? faces.entry : faces.exit;
            const int u = (axis + 1) % 3, v = (axis + 2) % 3;
            auto corner = [&](bool highU, bool highV) {
              glm::dvec3 p;
              p[axis] = plane;
              p[u] = highU ? hi[u] : lo[u];
              p[v] = highV ? hi[v] : lo[v];
              return glm::vec3(p);
            };
            triangles.insert(triangles.end(),
                             {corner(false, false), corner(true, false), corner(true, true),
                              corner(false, false), corner(true, true), corner(false, true)});
          }
        }
      }
    }
  }
  return faces;
}

namespace {
gl::ProgramSpec facesProgram(std::vector<std::string> defines) {
  return {{gl::ShaderSource::file("shaders/common.glsl"),
           gl::ShaderSource::file("shaders/occupied_faces.vert")},
          {gl::ShaderSource::file("shaders/common.glsl"),
           gl::ShaderSource::file("shaders/occupied_faces.frag")},
          {},
          std::move(defines)};
}
}  // namespace

EmptySpaceSkipping::EmptySpaceSkipping()
    : entryProgram_(facesProgram({})),
      depthAsColorProgram_(facesProgram({"DEPTH_AS_COLOR"})),
      buffer_(gl::createBuffer()),
      vertexArray_(gl::createVertexArray()) {
  VSIL_GL(glBindVertexArray(vertexArray_.id()));
  VSIL_GL(glBindBuffer(GL_ARRAY_BUFFER, buffer_.id()));
  VSIL_GL(glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(glm::vec3), nullptr));
  VSIL_GL(glEnableVertexAttribArray(0));
  glBindVertexArray(0);
}

void EmptySpaceSkipping::prepare(const BrickRanges& ranges, const BrickOccupancy& occupied,
                                 const View& view, bool enabled,
                                 const std::vector<bool>& alsoOccupied) {
  enabled_ = enabled;
  entryVertices_ = exitVertices_ = 0;
  if (!exitDepth_ || exitDepth_->size() != view.viewport) {
    exitDepth_.reset();
    exitDepth_.emplace(view.viewport, GL_R32F);
  }
  glDisable(GL_SCISSOR_TEST);
  exitDepth_->bindForDrawing();
  const GLfloat exitClear[4] = {enabled ? 0.0f : 1.0f, 0, 0, 0};
  VSIL_GL(glClearBufferfv(GL_COLOR, 0, exitClear));
  if (!enabled) return;

  OccupiedFaces faces = occupiedFaces(ranges, occupied, view, alsoOccupied);
  entryVertices_ = GLsizei(faces.entry.size());
  exitVertices_ = GLsizei(faces.exit.size());
  std::vector<glm::vec3>& vertices = faces.entry;  // entry faces first, then exit faces
  vertices.insert(vertices.end(), faces.exit.begin(), faces.exit.end());
  VSIL_GL(glBindBuffer(GL_ARRAY_BUFFER, buffer_.id()));
  VSIL_GL(glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(vertices.size() * sizeof(glm::vec3)),
                       vertices.data(), GL_STREAM_DRAW));

  gl::Blending farthest(GL_MAX, GL_ONE, GL_ONE);
  drawFaces(depthAsColorProgram_, glm::mat4(view.clipFromVoxel()), entryVertices_, exitVertices_);
}

void EmptySpaceSkipping::drawEntryDepthImage(const glm::mat4& clipFromVoxel) {
  const glm::ivec2 size = exitDepth_->size();  // prepare() made it for this frame's viewport
  if (!entryDepth_ || entryDepth_->size() != size) {
    entryDepth_.reset();
    entryDepth_.emplace(size, GL_R32F);
  }
  gl::Capability noScissor(GL_SCISSOR_TEST, false);
  entryDepth_->bindForDrawing();
  // As writeEntryDepth leaves the depth buffer: 1 where no ray enters, 0 everywhere unskipped.
  const GLfloat clear[4] = {enabled_ ? 1.0f : 0.0f, 0, 0, 0};
  VSIL_GL(glClearBufferfv(GL_COLOR, 0, clear));
  gl::Blending nearest(GL_MIN, GL_ONE, GL_ONE);
  drawFaces(depthAsColorProgram_, clipFromVoxel, 0, entryVertices_);
}

void EmptySpaceSkipping::writeEntryDepth(const glm::mat4& clipFromVoxel) {
  gl::Capability noScissor(GL_SCISSOR_TEST, false);
  gl::DepthTest nearest(GL_LESS, /*write=*/true);
  glStencilMask(0xFF);
  VSIL_GL(glClearBufferfi(GL_DEPTH_STENCIL, 0, enabled_ ? 1.0f : 0.0f, 0));
  gl::ColorMask depthOnly(false);
  drawFaces(entryProgram_, clipFromVoxel, 0, entryVertices_);
}

void EmptySpaceSkipping::drawFaces(gl::Program& program, const glm::mat4& clipFromVoxel,
                                   GLint first, GLsizei count) {
  if (count == 0) return;
  // Faces in front of the near plane (the margin reaches past the box) must not be clipped:
  // clamped to depth 0 they still open their pixels from the first slice on.
  gl::Capability depthClamp(GL_DEPTH_CLAMP, true);
  program.use();
  program.set("facesClipFromVoxel", clipFromVoxel);
  glBindVertexArray(vertexArray_.id());
  VSIL_GL(glDrawArrays(GL_TRIANGLES, first, count));
}

}  // namespace vsil
