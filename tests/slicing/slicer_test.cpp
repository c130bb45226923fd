// View-aligned slice planning: plane count, polygons on the plane and on the box.
#include <cmath>

#include <gtest/gtest.h>

#include "slicing/slicer.h"

namespace vsil {
namespace {

TEST(Slicer, AxisAlignedViewGivesOneSlicePerVoxel) {
  CameraSpec camera;
  camera.azimuthDeg = 0;
  camera.elevationDeg = 0;
  camera.orthographic = true;
  const View view = makeView(camera, {40, 30, 20}, {1, 1, 1}, {64, 64});
  const SlicePlan plan = planSlices(view, {40, 30, 20}, {1, 1, 1}, 1.0);
  // Looking along -z: the box is 20 voxels deep.
  EXPECT_EQ(plan.slices.size(), 20u);
  EXPECT_NEAR(view.farEye - view.nearEye, 20.0 / 40.0, 1e-12);  // world: longest side 1
  for (const Slice& slice : plan.slices) EXPECT_EQ(slice.polygonVoxel.size(), 4u);
}

TEST(Slicer, AnisotropicSpacingCountsVoxelsNotLength) {
  CameraSpec camera;
  camera.azimuthDeg = 0;
  camera.elevationDeg = 0;
  const View view = makeView(camera, {64, 64, 16}, {1, 1, 4}, {64, 64});
  EXPECT_EQ(planSlices(view, {64, 64, 16}, {1, 1, 4}, 1.0).slices.size(), 16u);
  EXPECT_EQ(planSlices(view, {64, 64, 16}, {1, 1, 4}, 2.0).slices.size(), 32u);
}

TEST(Slicer, PolygonsLieOnTheirPlaneAndOnTheBoxSurface) {
  CameraSpec camera;
  camera.azimuthDeg = 33;
  camera.elevationDeg = 27;
  const glm::ivec3 dims(50, 40, 30);
  const View view = makeView(camera, dims, {1, 1, 1}, {100, 80});
  const SlicePlan plan = planSlices(view, dims, {1, 1, 1}, 1.0);
  ASSERT_GT(plan.slices.size(), 30u);
  for (const Slice& slice : plan.slices) {
    ASSERT_GE(slice.polygonVoxel.size(), 3u);
    ASSERT_LE(slice.polygonVoxel.size(), 6u);
    for (const glm::dvec3& p : slice.polygonVoxel) {
      const double distance = -(view.eyeFromVoxel * glm::dvec4(p, 1.0)).z;
      EXPECT_NEAR(distance, slice.eyeDistance, 1e-9);
      // On the surface: inside the box, and on at least one face.
      double toFace = 1e9;
      for (int axis = 0; axis < 3; ++axis) {
        EXPECT_GE(p[axis], -0.5 - 1e-9);
        EXPECT_LE(p[axis], dims[axis] - 0.5 + 1e-9);
        toFace = std::min({toFace, std::abs(p[axis] + 0.5), std::abs(p[axis] - dims[axis] + 0.5)});
      }
      EXPECT_LT(toFace, 1e-9);
    }
  }
  // Front to back, evenly spaced, half a step inside the box's depth range.
  EXPECT_NEAR(plan.slices.front().eyeDistance, view.nearEye + plan.stepEye / 2, 1e-12);
  EXPECT_NEAR(plan.slices.back().eyeDistance, view.farEye - plan.stepEye / 2, 1e-9);
}

TEST(Slicer, PlaneOutsideTheBoxGivesNoPolygon) {
  CameraSpec camera;
  const View view = makeView(camera, {8, 8, 8}, {1, 1, 1}, {16, 16});
  EXPECT_TRUE(slicePolygon(view, {8, 8, 8}, view.nearEye - 0.1).empty());
  EXPECT_TRUE(slicePolygon(view, {8, 8, 8}, view.farEye + 0.1).empty());
}

}  // namespace
}  // namespace vsil
