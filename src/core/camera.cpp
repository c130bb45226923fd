#include "core/camera.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/gtc/matrix_transform.hpp>

namespace vsil {

glm::dvec3 View::eyeAtNdc(glm::dvec2 ndc, double distance) const {
  const double scale = orthographic ? 1.0 : distance;
  return {ndc.x * halfExtent.x * scale, ndc.y * halfExtent.y * scale, -distance};
}

glm::dvec2 View::ndcFromPixel(glm::dvec2 pixel) const {
  return {2.0 * pixel.x / viewport.x - 1.0, 1.0 - 2.0 * pixel.y / viewport.y};
}

glm::dvec3 View::viewDirectionWorld() const {
  // -z of the eye, expressed in world coordinates (eyeFromWorld is a rigid motion).
  const glm::dmat3 worldFromEyeRotation = glm::transpose(glm::dmat3(eyeFromWorld));
  return glm::normalize(worldFromEyeRotation * glm::dvec3(0, 0, -1));
}

View makeView(const CameraSpec& camera, glm::ivec3 dims, glm::dvec3 spacing, glm::ivec2 viewport) {
  View view;
  view.viewport = viewport;
  view.orthographic = camera.orthographic;

  const glm::dvec3 extent = glm::dvec3(dims) * spacing;
  const double longest = std::max({extent.x, extent.y, extent.z});
  const glm::dvec3 centreVoxel = (glm::dvec3(dims) - 1.0) * 0.5;
  view.worldFromVoxel = glm::scale(glm::dmat4(1.0), spacing / longest) *
                        glm::translate(glm::dmat4(1.0), -centreVoxel);
  const double radius = 0.5 * glm::length(extent / longest);  // bounding sphere of the box

  const double fovHalf = glm::radians(std::clamp(camera.fovYDeg, 1.0, 170.0)) * 0.5;
  const double distance = camera.orthographic ? 2.0 * radius + 1.0 : radius / std::sin(fovHalf);
  const double az = glm::radians(camera.azimuthDeg);
  const double el = glm::radians(camera.elevationDeg);
  // The orbit in the upright frame (its +y up, +z front; right = up × front keeps it a
  // rotation), laid onto the world's axes.
  const Upright& upright = camera.upright;
  const glm::dmat4 worldFromUpright(
      glm::dmat3(glm::cross(upright.up, upright.front), upright.up, upright.front));
  // worldFromEye = upright * rotY(az) * rotX(-el) * translate(0, 0, distance): the eye orbits
  // the centre.
  glm::dmat4 worldFromEye = worldFromUpright *
                            glm::rotate(glm::dmat4(1.0), az, glm::dvec3(0, 1, 0)) *
                            glm::rotate(glm::dmat4(1.0), -el, glm::dvec3(1, 0, 0)) *
                            glm::translate(glm::dmat4(1.0), glm::dvec3(0, 0, distance));
  view.eyeFromWorld = glm::inverse(worldFromEye);
  view.eyeFromVoxel = view.eyeFromWorld * view.worldFromVoxel;

  double nearEye = std::numeric_limits<double>::max();
  double farEye = std::numeric_limits<double>::lowest();
  for (int corner = 0; corner < 8; ++corner) {
    const glm::dvec3 voxel((corner & 1) ? dims.x - 0.5 : -0.5, (corner & 2) ? dims.y - 0.5 : -0.5,
                           (corner & 4) ? dims.z - 0.5 : -0.5);
    const double eyeDistance = -(view.eyeFromVoxel * glm::dvec4(voxel, 1.0)).z;
    nearEye = std::min(nearEye, eyeDistance);
    farEye = std::max(farEye, eyeDistance);
  }
  view.nearEye = nearEye;
  view.farEye = farEye;

  const double aspect = double(viewport.x) / double(viewport.y);
  const double zoom = camera.zoom > 0 ? camera.zoom : 1.0;
  // The bounding sphere fills the smaller image side at zoom 1.
  const double halfMin = camera.orthographic ? radius / zoom : std::tan(fovHalf) / zoom;
  view.halfExtent =
      aspect >= 1.0 ? glm::dvec2(halfMin * aspect, halfMin) : glm::dvec2(halfMin, halfMin / aspect);
  // Clip planes with a margin around the box so no slice touches them.
  const double margin = 0.01 * (farEye - nearEye) + 1e-3;
  const double clipNear = camera.orthographic ? nearEye - margin : std::max(nearEye - margin, 1e-3);
  const double clipFar = farEye + margin;
  if (camera.orthographic) {
    view.clipFromEye = glm::ortho(-view.halfExtent.x, view.halfExtent.x, -view.halfExtent.y,
                                  view.halfExtent.y, clipNear, clipFar);
  } else {
    view.clipFromEye = glm::frustum(-view.halfExtent.x * clipNear, view.halfExtent.x * clipNear,
                                    -view.halfExtent.y * clipNear, view.halfExtent.y * clipNear,
                                    clipNear, clipFar);
  }
  return view;
}

}  // namespace vsil
