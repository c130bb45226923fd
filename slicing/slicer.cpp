#include "slicing/slicer.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/error.h"
#include "core/limits.h"

namespace vsil {

PixelRect PixelRect::united(const PixelRect& other) const {
  if (empty()) return other;
  if (other.empty()) return *this;
  return {std::min(x0, other.x0), std::min(y0, other.y0), std::max(x1, other.x1),
          std::max(y1, other.y1)};
}

PixelRect PixelRect::grown(int pixels, glm::ivec2 viewport) const {
  if (empty()) return *this;
  return {std::max(0, x0 - pixels), std::max(0, y0 - pixels), std::min(viewport.x, x1 + pixels),
          std::min(viewport.y, y1 + pixels)};
}

SliceVoxelCoords sliceVoxelCoords(const View& view, double eyeDistance) {
  // eye = (ndc.x * h.x * s, ndc.y * h.y * s, -d) with s = d (perspective) or 1; voxel = M eye.
  const glm::dmat4 voxelFromEye = glm::inverse(view.eyeFromVoxel);
  const double scale = view.orthographic ? 1.0 : eyeDistance;
  SliceVoxelCoords coords;
  coords.perNdcX = glm::vec3(glm::dvec3(voxelFromEye[0]) * (view.halfExtent.x * scale));
  coords.perNdcY = glm::vec3(glm::dvec3(voxelFromEye[1]) * (view.halfExtent.y * scale));
  coords.atNdcOrigin =
      glm::vec3(glm::dvec3(voxelFromEye[3]) - glm::dvec3(voxelFromEye[2]) * eyeDistance);
  return coords;
}

PixelRays pixelRays(const View& view, const SlicePlan& plan) {
  // The sample on the plane at eye distance e: voxel = M (ndc.x h.x s, ndc.y h.y s, -e, 1) with
  // s = e (perspective) or 1, M = voxelFromEye, e = firstEye + t, ndc = w * 2 / viewport - 1.
  const double firstEye = plan.slices.empty() ? view.nearEye : plan.slices.front().eyeDistance;
  const glm::dmat4 m = glm::inverse(view.eyeFromVoxel);
  const glm::dvec3 alongX = glm::dvec3(m[0]) * view.halfExtent.x;  // per unit of NDC x
  const glm::dvec3 alongY = glm::dvec3(m[1]) * view.halfExtent.y;
  const glm::dvec3 forward = -glm::dvec3(m[2]);
  const glm::dvec3 onFirstPlane = glm::dvec3(m[3]) + forward * firstEye;
  const glm::dvec2 ndcPerWindow = 2.0 / glm::dvec2(view.viewport);
  // An affine function of NDC, ndc.x * x + ndc.y * y + a, as one of window coordinates.
  struct Affine {
    glm::dvec3 x, y, a;
  };
  const auto inWindow = [&](const Affine& f, glm::vec3& perX, glm::vec3& perY, glm::vec3& at) {
    perX = glm::vec3(f.x * ndcPerWindow.x);
    perY = glm::vec3(f.y * ndcPerWindow.y);
    at = glm::vec3(f.a - f.x - f.y);
  };
  const double scale = view.orthographic ? 1.0 : firstEye;
  const Affine origin{alongX * scale, alongY * scale, onFirstPlane};
  const Affine direction = view.orthographic ? Affine{glm::dvec3(0.0), glm::dvec3(0.0), forward}
                                             : Affine{alongX, alongY, forward};
  PixelRays rays;
  inWindow(origin, rays.originPerWindowX, rays.originPerWindowY, rays.originAtWindowOrigin);
  inWindow(direction, rays.directionPerWindowX, rays.directionPerWindowY,
           rays.directionAtWindowOrigin);
  rays.stepEye = float(plan.stepEye);
  return rays;
}

std::vector<glm::dvec3> slicePolygon(const View& view, glm::ivec3 dims, double eyeDistance) {
  return boxSlicePolygon(view, glm::dvec3(-0.5), glm::dvec3(dims) - 0.5, eyeDistance);
}

std::vector<glm::dvec3> boxSlicePolygon(const View& view, glm::dvec3 lo, glm::dvec3 hi,
                                        double eyeDistance) {
  auto corner = [&](int i) {
    return glm::dvec3((i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z);
  };
  auto distanceOf = [&](const glm::dvec3& voxel) {
    return -(view.eyeFromVoxel * glm::dvec4(voxel, 1.0)).z;
  };
  std::vector<glm::dvec3> points;
  // The 12 box edges join corners differing in one bit.
  for (int a = 0; a < 8; ++a) {
    for (int bit = 1; bit < 8; bit <<= 1) {
      if (a & bit) continue;
      const int b = a | bit;
      const glm::dvec3 pa = corner(a), pb = corner(b);
      const double da = distanceOf(pa) - eyeDistance, db = distanceOf(pb) - eyeDistance;
      if ((da < 0) == (db < 0)) continue;  // both on one side (a touch counts once, below)
      const double t = da / (da - db);
      points.push_back(pa + t * (pb - pa));
    }
  }
  if (points.size() < 3) return {};
  // Order around the centroid by angle in the eye's xy-plane.
  glm::dvec2 centre(0.0);
  std::vector<glm::dvec2> projected;
  for (const auto& p : points) {
    const glm::dvec4 eye = view.eyeFromVoxel * glm::dvec4(p, 1.0);
    projected.emplace_back(eye.x, eye.y);
    centre += projected.back();
  }
  centre /= double(points.size());
  std::vector<std::size_t> order(points.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return std::atan2(projected[a].y - centre.y, projected[a].x - centre.x) <
           std::atan2(projected[b].y - centre.y, projected[b].x - centre.x);
  });
  std::vector<glm::dvec3> polygon;
  for (std::size_t i : order) polygon.push_back(points[i]);
  return polygon;
}

namespace {

// The part of a convex polygon on one side of the plane p[axis] = c (side < 0: p[axis] <= c;
// side > 0: p[axis] >= c). A vertex on the plane belongs to both sides; a cut vertex is
// computed from its edge's end points in lexicographic order, so both sides get the same one.
std::vector<glm::dvec3> clipPolygon(const std::vector<glm::dvec3>& polygon, int axis, double c,
                                    int side) {
  std::vector<glm::dvec3> out;
  const std::size_t n = polygon.size();
  auto inside = [&](const glm::dvec3& p) { return side < 0 ? p[axis] <= c : p[axis] >= c; };
  for (std::size_t i = 0; i < n; ++i) {
    const glm::dvec3& a = polygon[i];
    const glm::dvec3& b = polygon[(i + 1) % n];
    if (inside(a)) out.push_back(a);
    // The edge crosses the plane strictly (neither end on it).
    const bool crosses = (a[axis] < c && b[axis] > c) || (a[axis] > c && b[axis] < c);
    if (crosses) {
      const bool ordered = std::lexicographical_compare(&a[0], &a[0] + 3, &b[0], &b[0] + 3);
      const glm::dvec3& p = ordered ? a : b;
      const glm::dvec3& q = ordered ? b : a;
      const double t = (c - p[axis]) / (q[axis] - p[axis]);
      glm::dvec3 cut = p + t * (q - p);
      cut[axis] = c;
      out.push_back(cut);
    }
  }
  if (out.size() < 3) out.clear();
  return out;
}

}  // namespace

double pieceMargin(const SlicePlan& plan) {
  return std::max(kPieceMargin, 1.25 * plan.stepVoxels);
}

std::vector<SlicePiece> slicePieces(const View& view, const BrickLayout& layout, double eyeDistance,
                                    double margin, double overlap) {
  const glm::dvec3 lo(-0.5 - margin);
  const glm::dvec3 hi = glm::dvec3(layout.dims()) - 0.5 + margin;
  const std::vector<glm::dvec3> polygon = boxSlicePolygon(view, lo, hi, eyeDistance);
  std::vector<SlicePiece> pieces;
  if (polygon.empty()) return pieces;
  const glm::ivec3 counts = layout.counts();
  const auto& bricks = layout.bricks();
  auto brickAt = [&](int i, int j, int k) -> const Brick& {
    return bricks[(std::size_t(k) * counts.y + std::size_t(j)) * counts.x + std::size_t(i)];
  };
  // x, then y, then z: every piece is cut by the same planes in the same order.
  for (int i = 0; i < counts.x; ++i) {
    std::vector<glm::dvec3> strip = polygon;
    const Brick& bx = brickAt(i, 0, 0);
    if (i > 0) strip = clipPolygon(strip, 0, bx.low.x - overlap, +1);
    if (i + 1 < counts.x) strip = clipPolygon(strip, 0, bx.high.x + overlap, -1);
    if (strip.empty()) continue;
    for (int j = 0; j < counts.y; ++j) {
      std::vector<glm::dvec3> bar = strip;
      const Brick& by = brickAt(0, j, 0);
      if (j > 0) bar = clipPolygon(bar, 1, by.low.y - overlap, +1);
      if (j + 1 < counts.y) bar = clipPolygon(bar, 1, by.high.y + overlap, -1);
      if (bar.empty()) continue;
      for (int k = 0; k < counts.z; ++k) {
        std::vector<glm::dvec3> piece = bar;
        const Brick& bz = brickAt(0, 0, k);
        if (k > 0) piece = clipPolygon(piece, 2, bz.low.z - overlap, +1);
        if (k + 1 < counts.z) piece = clipPolygon(piece, 2, bz.high.z + overlap, -1);
        if (piece.empty()) continue;
        pieces.push_back({(std::size_t(k) * counts.y + std::size_t(j)) * counts.x + std::size_t(i),
                          std::move(piece)});
      }
    }
  }
  return pieces;
}

SlicePlan planSlices(const View& view, glm::ivec3 dims, glm::dvec3 spacing,
                     double samplesPerVoxel) {
  if (!(samplesPerVoxel > 0) || !std::isfinite(samplesPerVoxel)) {
    throw std::invalid_argument("planSlices: samples per voxel must be positive");
  }
  // Voxels crossed per unit of eye (= world) distance along the view direction.
  const glm::dvec3 extent = glm::dvec3(dims) * spacing;
  const double longest = std::max({extent.x, extent.y, extent.z});
  const glm::dvec3 directionVoxel = view.viewDirectionWorld() * (longest / spacing);
  const double voxelsPerUnit = glm::length(directionVoxel);
  const double range = view.farEye - view.nearEye;
  // Checked as a double: an extreme spacing ratio makes it more than an int holds (the render
  // job refuses such volumes first, limits::sliceCountBound; this guards every other caller).
  const double wanted = std::round(range * voxelsPerUnit * samplesPerVoxel);
  if (!(wanted <= double(limits::kMaxSlices))) {
    throw InputError("a frame would need more slices than the limit of " +
                     std::to_string(limits::kMaxSlices) + " (the spacing's axes differ too much)");
  }
  const int count = std::max(1, int(wanted));
  SlicePlan plan;
  plan.stepEye = range / count;
  plan.stepVoxels = plan.stepEye * voxelsPerUnit;
  plan.slices.reserve(std::size_t(count));
  for (int k = 0; k < count; ++k) {
    Slice slice;
    slice.eyeDistance = view.nearEye + (k + 0.5) * plan.stepEye;
    slice.depth = (k + 0.5) / count;
    slice.polygonVoxel = slicePolygon(view, dims, slice.eyeDistance);
    plan.slices.push_back(std::move(slice));
  }
  return plan;
}

PixelRect polygonPixelBounds(const View& view, const std::vector<glm::dvec3>& polygonVoxel) {
  if (polygonVoxel.empty()) return {};
  double minX = 1e300, minY = 1e300, maxX = -1e300, maxY = -1e300;
  const glm::dmat4 clipFromVoxel = view.clipFromVoxel();
  for (const auto& p : polygonVoxel) {
    const glm::dvec4 clip = clipFromVoxel * glm::dvec4(p, 1.0);
    const double px = (clip.x / clip.w + 1.0) * 0.5 * view.viewport.x;
    const double py = (1.0 - clip.y / clip.w) * 0.5 * view.viewport.y;
    minX = std::min(minX, px);
    maxX = std::max(maxX, px);
    minY = std::min(minY, py);
    maxY = std::max(maxY, py);
  }
  // Clamp before converting: the box may extend far beyond a zoomed-in viewport.
  auto clampX = [&](double x) { return std::clamp(x, -1.0, view.viewport.x + 1.0); };
  auto clampY = [&](double y) { return std::clamp(y, -1.0, view.viewport.y + 1.0); };
  PixelRect rect{int(std::floor(clampX(minX))), int(std::floor(clampY(minY))),
                 int(std::ceil(clampX(maxX))) + 1, int(std::ceil(clampY(maxY))) + 1};
  return rect.grown(0, view.viewport);
}

}  // namespace vsil
