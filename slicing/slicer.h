#pragma once
// View-aligned slicing: planes perpendicular to the view direction (constant eye distance),
// front to back, each cut with the volume's box into a convex polygon of 3 to 6 vertices.
// Pure geometry, no GL: the CPU references use the same plan.
#include <vector>

#include <glm/glm.hpp>

#include "core/brick_layout.h"
#include "core/camera.h"

namespace vsil {

struct Slice {
  double eyeDistance = 0;                // -z_eye of the plane
  double depth = 0;                      // normalized depth d of the plane (View::normalizedDepth)
  std::vector<glm::dvec3> polygonVoxel;  // box ∩ plane in voxel coordinates, convex, ordered
};

// Where pixel centres sample the volume on the plane at eye distance d, as the slice shaders
// compute it (common.glsl sliceVoxel): voxel coordinates affine in the pixel's NDC,
// voxel = ndc.x * perNdcX + ndc.y * perNdcY + atNdcOrigin, in float (then rounded to
// BrickLayout::kSampleQuantum). Computed in double and rounded once, so the CPU references can
// repeat the shader's arithmetic.
struct SliceVoxelCoords {
  glm::vec3 perNdcX{0.0f};
  glm::vec3 perNdcY{0.0f};
  glm::vec3 atNdcOrigin{0.0f};
};
SliceVoxelCoords sliceVoxelCoords(const View& view, double eyeDistance);

// The MIP family's sampling (mip, demip, lmip; common.glsl RAY_SAMPLING): each pixel's ray in
// voxel coordinates from the plan's first plane, one unit of t per unit of eye distance, its
// origin and direction affine in the pixel centre's window coordinates w (gl_FragCoord.xy:
// x + 0.5, y + 0.5, rows bottom-up, exact in float):
//   origin    = w.x * originPerWindowX + w.y * originPerWindowY + originAtWindowOrigin
//   direction = w.x * directionPerWindowX + w.y * directionPerWindowY + directionAtWindowOrigin
// and slice k's sample at origin + t * direction with t = float(k) * stepEye, in float (then
// rounded to BrickLayout::kSampleQuantum). Their marches compute a pixel's ray once and then 4
// operations per sample, reading nothing per slice (a quarter to a third off a MIP frame: llvmpipe
// reads a uniform block at a loop counter lane by lane); their slice passes (volumes in bricks)
// compute the same per fragment, so both sample the same positions. The other techniques keep
// SliceVoxelCoords: 6 operations per fragment against 15 here, which measured about a tenth of
// a first-hit slice pass. The same points as SliceVoxelCoords in exact arithmetic; the
// coefficients come from the view in double, rounded once, for the CPU references to repeat.
struct PixelRays {
  glm::vec3 originPerWindowX{0.0f}, originPerWindowY{0.0f}, originAtWindowOrigin{0.0f};
  glm::vec3 directionPerWindowX{0.0f}, directionPerWindowY{0.0f}, directionAtWindowOrigin{0.0f};
  float stepEye = 0;  // SlicePlan::stepEye
};

// The #define that makes a slice pass sample along PixelRays (common.glsl sliceVoxel) where
// its technique's march does.
inline constexpr const char* kRaySamplingDefine = "RAY_SAMPLING";

// The pieces of a slice polygon, one per brick it crosses (core/brick_layout.h): the plane cut
// with the volume's box grown by kPieceMargin voxels (pixels there fail the shaders' inside
// test, so where the outer edges fall never matters: the inside test decides, as in the CPU
// references; with the polygon cut at the box itself, rasterisation decided pixel centres on
// its edge, and the bonsai, engine and Marschner–Lobb scenes of gl_vs_reference_test.cpp
// disagree with the references), then with each brick's owned region.
// Neighbouring pieces share their cut vertices bit for bit (each computed once per edge, from
// its end points in a fixed order), so every pixel of the polygon is drawn by exactly one piece.
struct SlicePiece {
  std::size_t brick = 0;  // index in BrickLayout::bricks()
  std::vector<glm::dvec3> polygonVoxel;
};
// `margin` (voxels, at least kPieceMargin): pixels whose sample lies off the plane, up to that
// far (common.glsl BOX_ALIGNED_SAMPLING: up to one step in front), still get a fragment.
inline constexpr double kPieceMargin = 1.0;
// With `overlap` > 0 each piece reaches that far (voxels) into its neighbours' bricks, so that
// pieces overlap and a pixel may be drawn by several: for samples off the plane, whose shader
// keeps only the one its brick owns (common.glsl ownedByBrick).
std::vector<SlicePiece> slicePieces(const View& view, const BrickLayout& layout, double eyeDistance,
                                    double margin = kPieceMargin, double overlap = 0.0);
// The margin for a plan: a step along the view and a quarter more for perspective rays off the
// axis (the box-aligned samples lie up to a step in front of their plane).
struct SlicePlan;
double pieceMargin(const SlicePlan& plan);

// Pixel rectangle [x0, x1) x [y0, y1) in image pixels (origin top-left); empty when x0 >= x1.
struct PixelRect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  bool empty() const { return x0 >= x1 || y0 >= y1; }
  PixelRect united(const PixelRect& other) const;
  PixelRect grown(int pixels, glm::ivec2 viewport) const;  // clamped to the viewport
};

struct SlicePlan {
  double stepEye = 0;  // distance between consecutive planes
  // The same distance in voxels along the view direction (anisotropic spacing counted), about
  // 1 / samplesPerVoxel: the opacity correction's Δ/Δ₀ with Δ₀ one voxel (compositing.h).
  double stepVoxels = 0;
  std::vector<Slice> slices;
};

// Slices every `1 / samplesPerVoxel` voxels along the view direction (anisotropic spacing
// counted), spread evenly over the box's eye-distance range [nearEye, farEye] with the first
// and last plane half a step inside it.
SlicePlan planSlices(const View& view, glm::ivec3 dims, glm::dvec3 spacing, double samplesPerVoxel);

// The pixels' rays through the plan's slices (its first plane, its step).
PixelRays pixelRays(const View& view, const SlicePlan& plan);

// Box ∩ plane at eye distance `eyeDistance`, in voxel coordinates; empty if they miss.
std::vector<glm::dvec3> slicePolygon(const View& view, glm::ivec3 dims, double eyeDistance);
// The same for the box [lo, hi].
std::vector<glm::dvec3> boxSlicePolygon(const View& view, glm::dvec3 lo, glm::dvec3 hi,
                                        double eyeDistance);

// The pixels whose centres may fall inside the polygon (its projected bounding box, rounded
// outwards), clamped to the viewport.
PixelRect polygonPixelBounds(const View& view, const std::vector<glm::dvec3>& polygonVoxel);

}  // namespace vsil
