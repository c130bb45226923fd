#pragma once
// Cameras and the spaces they connect. Names read like the math: eyeFromVoxel maps a point in
// voxel coordinates to eye coordinates.
//
// Spaces:
//  voxel  voxel indices: i along the file's fastest axis, sample centres at integers; the
//         volume's box (the 3D texture's extent) is [-0.5, dim - 0.5] on each axis.
//  world  the box centred at the origin, scaled by the spacing so its longest side is 1.
//  eye    right-handed, the camera at the origin looking down -z, +y up (OpenGL convention).
//         The "eye distance" of a point is -z_eye, its distance along the view direction.
//  clip / ndc  OpenGL clip space; ndc x = -1 is the image's left edge, ndc y = +1 its top edge.
//  pixel  image pixels, origin at the top-left corner, x right, y down, centres at +0.5.
#include <glm/glm.hpp>

namespace vsil {

// The world axes the camera's orbit is laid out by: `up` shows upward on screen and the orbit
// turns about it; `front` faces the viewer at azimuth 0, elevation 0. Unit and perpendicular
// (core/upright.h resolves --up into them: +y and +z, or a file's superior and anterior).
struct Upright {
  glm::dvec3 up{0, 1, 0};
  glm::dvec3 front{0, 0, 1};
};

struct CameraSpec {
  double azimuthDeg = 30.0;    // orbit around `upright.up`; 0 looks at the volume from its front
  double elevationDeg = 20.0;  // orbit up towards `upright.up`; 90 looks straight down
  double zoom = 1.0;           // > 1 magnifies
  bool orthographic = false;
  double fovYDeg = 30.0;  // perspective only, before zoom
  Upright upright{};
};

// Everything needed to go from a voxel to a pixel, fixed for one frame.
struct View {
  glm::ivec2 viewport{0};  // width, height in pixels
  glm::dmat4 worldFromVoxel{1.0};
  glm::dmat4 eyeFromWorld{1.0};
  glm::dmat4 eyeFromVoxel{1.0};
  glm::dmat4 clipFromEye{1.0};
  bool orthographic = false;
  // Eye distances (-z_eye) of the volume box's nearest and farthest corners. The normalized
  // depth d of a point maps its eye distance linearly from [nearEye, farEye] to [0, 1].
  double nearEye = 0.0;
  double farEye = 0.0;
  // Half extents of the view at eye distance 1 (perspective) or anywhere (orthographic):
  // x_eye = ndc_x * halfExtent.x * (orthographic ? 1 : distance).
  glm::dvec2 halfExtent{1.0};

  glm::dmat4 clipFromVoxel() const { return clipFromEye * eyeFromVoxel; }
  // The eye-space point seen through NDC (x, y) at eye distance `distance`.
  glm::dvec3 eyeAtNdc(glm::dvec2 ndc, double distance) const;
  glm::dvec2 ndcFromPixel(glm::dvec2 pixel) const;
  double normalizedDepth(double eyeDistance) const {
    return (eyeDistance - nearEye) / (farEye - nearEye);
  }
  // Unit view direction (towards the scene) in voxel coordinates scaled by spacing, i.e. world.
  glm::dvec3 viewDirectionWorld() const;
};

// Builds the view of a volume with `dims` samples spaced by `spacing`, fitted so the box's
// bounding sphere fills the smaller image side at zoom 1.
View makeView(const CameraSpec& camera, glm::ivec3 dims, glm::dvec3 spacing, glm::ivec2 viewport);

}  // namespace vsil
