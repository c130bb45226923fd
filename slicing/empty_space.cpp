#include "slicing/empty_space.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace vsil {

namespace {

constexpr int kB = BrickMaxima::kBrickSize;

// The voxels brick k reads along one axis: positions [kB - 0.5, (k+1)B - 0.5] filter voxels
// kB - 1 .. (k+1)B; one more on each side absorbs rounding of the sample position.
int firstVoxel(int brick) {
  return brick * kB - 2;
}
int lastVoxel(int brick) {
  return (brick + 1) * kB + 1;
}

}  // namespace

BrickMaxima::BrickMaxima(const Volume& volume)
    : dims_(volume.dims), bricks_((volume.dims + kB - 1) / kB) {
  const float lowest = -std::numeric_limits<float>::infinity();
  // Separable maxima: along x per row, then y, then z.
  auto voxelRange = [](int brick, int dim) {
    return std::pair{std::max(0, firstVoxel(brick)), std::min(dim - 1, lastVoxel(brick))};
  };
  const glm::ivec3 d = dims_, b = bricks_;
  std::vector<float> alongX(std::size_t(b.x) * d.y * d.z, lowest);
  volume.visit([&](auto samples) {
    for (int z = 0; z < d.z; ++z) {
      for (int y = 0; y < d.y; ++y) {
        const auto* row = &samples[volume.index(0, y, z)];
        for (int bx = 0; bx < b.x; ++bx) {
          const auto [x0, x1] = voxelRange(bx, d.x);
          alongX[(std::size_t(z) * d.y + y) * b.x + bx] =
              float(*std::max_element(row + x0, row + x1 + 1));
        }
      }
    }
  });
  std::vector<float> alongY(std::size_t(b.x) * b.y * d.z, lowest);
  for (int z = 0; z < d.z; ++z) {
    for (int by = 0; by < b.y; ++by) {
      const auto [y0, y1] = voxelRange(by, d.y);
      for (int y = y0; y <= y1; ++y) {
        for (int bx = 0; bx < b.x; ++bx) {
          float& m = alongY[(std::size_t(z) * b.y + by) * b.x + bx];
          m = std::max(m, alongX[(std::size_t(z) * d.y + y) * b.x + bx]);
        }
      }
    }
  }
  maxima_.assign(std::size_t(b.x) * b.y * b.z, lowest);
  for (int bz = 0; bz < b.z; ++bz) {
    const auto [z0, z1] = voxelRange(bz, d.z);
    for (int z = z0; z <= z1; ++z) {
      for (int by = 0; by < b.y; ++by) {
        for (int bx = 0; bx < b.x; ++bx) {
          float& m = maxima_[(std::size_t(bz) * b.y + by) * b.x + bx];
          m = std::max(m, alongY[(std::size_t(z) * b.y + by) * b.x + bx]);
        }
      }
    }
  }
}

float BrickMaxima::maximum(glm::ivec3 brick) const {
  return maxima_[(std::size_t(brick.z) * bricks_.y + brick.y) * bricks_.x + brick.x];
}

bool BrickMaxima::occupied(glm::ivec3 brick, float iso) const {
  const float m = maximum(brick);
  return m >= iso - 1e-5f * (std::abs(iso) + std::abs(m));
}

glm::dvec3 BrickMaxima::regionLow(glm::ivec3 brick) const {
  return glm::dvec3(brick * kB) - 0.5;
}

glm::dvec3 BrickMaxima::regionHigh(glm::ivec3 brick) const {
  return glm::min(glm::dvec3((brick + 1) * kB), glm::dvec3(dims_)) - 0.5;
}

OccupiedFaces occupiedFaces(const BrickMaxima& maxima, float iso, const View& view) {
  const glm::dmat4 voxelFromEye = glm::inverse(view.eyeFromVoxel);
  // Perspective: a face is turned to the eye when the eye lies beyond its plane; orthographic:
  // when the direction towards the eye points out of it.
  const glm::dvec3 eye(voxelFromEye * glm::dvec4(0, 0, 0, 1));
  const glm::dvec3 towardsEye(voxelFromEye * glm::dvec4(0, 0, 1, 0));
  const glm::ivec3 bricks = maxima.bricks();
  OccupiedFaces faces;
  auto isOccupied = [&](glm::ivec3 b) {
    return glm::all(glm::greaterThanEqual(b, glm::ivec3(0))) &&
           glm::all(glm::lessThan(b, bricks)) && maxima.occupied(b, iso);
  };
  for (int bz = 0; bz < bricks.z; ++bz) {
    for (int by = 0; by < bricks.y; ++by) {
      for (int bx = 0; bx < bricks.x; ++bx) {
        const glm::ivec3 brick(bx, by, bz);
        if (!maxima.occupied(brick, iso)) continue;
        const glm::dvec3 lo = maxima.regionLow(brick) - kEntryMargin;
        const glm::dvec3 hi = maxima.regionHigh(brick) + kEntryMargin;
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

EmptySpaceSkipping::EmptySpaceSkipping()
    : entryProgram_("slice.vert", "occupied_faces.frag"),
      exitProgram_("slice.vert", "occupied_faces.frag", "#define EXIT_DEPTH 1"),
      buffer_(gl::createBuffer()),
      vertexArray_(gl::createVertexArray()) {
  VSIL_GL(glBindVertexArray(vertexArray_.id()));
  VSIL_GL(glBindBuffer(GL_ARRAY_BUFFER, buffer_.id()));
  VSIL_GL(glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(glm::vec3), nullptr));
  VSIL_GL(glEnableVertexAttribArray(0));
  glBindVertexArray(0);
}

void EmptySpaceSkipping::prepare(const BrickMaxima& maxima, float iso, const View& view,
                                 bool enabled) {
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

  OccupiedFaces faces = occupiedFaces(maxima, iso, view);
  entryVertices_ = GLsizei(faces.entry.size());
  exitVertices_ = GLsizei(faces.exit.size());
  std::vector<glm::vec3>& vertices = faces.entry;  // entry faces first, then exit faces
  vertices.insert(vertices.end(), faces.exit.begin(), faces.exit.end());
  VSIL_GL(glBindBuffer(GL_ARRAY_BUFFER, buffer_.id()));
  VSIL_GL(glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(vertices.size() * sizeof(glm::vec3)),
                       vertices.data(), GL_STREAM_DRAW));

  const glm::mat4 clipFromVoxel(view.clipFromVoxel());
  glEnable(GL_BLEND);
  glBlendEquation(GL_MAX);
  drawFaces(exitProgram_, clipFromVoxel, entryVertices_, exitVertices_);
  glBlendEquation(GL_FUNC_ADD);
  glDisable(GL_BLEND);
}

void EmptySpaceSkipping::writeEntryDepth(const glm::mat4& clipFromVoxel) {
  glDisable(GL_SCISSOR_TEST);
  glDepthMask(GL_TRUE);
  glStencilMask(0xFF);
  VSIL_GL(glClearBufferfi(GL_DEPTH_STENCIL, 0, enabled_ ? 1.0f : 0.0f, 0));
  glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  drawFaces(entryProgram_, clipFromVoxel, 0, entryVertices_);
  glDisable(GL_DEPTH_TEST);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
}

void EmptySpaceSkipping::drawFaces(gl::Program& program, const glm::mat4& clipFromVoxel,
                                   GLint first, GLsizei count) {
  if (count == 0) return;
  // Faces in front of the near plane (the margin reaches past the box) must not be clipped:
  // clamped to depth 0 they still open their pixels from the first slice on.
  glEnable(GL_DEPTH_CLAMP);
  program.use();
  program.set("clipFromVoxel", clipFromVoxel);
  glBindVertexArray(vertexArray_.id());
  VSIL_GL(glDrawArrays(GL_TRIANGLES, first, count));
  glDisable(GL_DEPTH_CLAMP);
}

}  // namespace vsil
