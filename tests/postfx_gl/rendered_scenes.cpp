#include "rendered_scenes.h"

#include "gl_harness.h"

namespace vsil::test {

RenderResult renderOrthographic(const Volume& volume, glm::ivec2 size, double azimuthDeg,
                                double elevationDeg) {
  RenderSettings settings;
  settings.technique = "silhouette";
  settings.size = size;
  settings.options["iso"] = 0.5;
  settings.camera.orthographic = true;
  settings.camera.azimuthDeg = azimuthDeg;
  settings.camera.elevationDeg = elevationDeg;
  Renderer renderer(sharedGlContext());
  renderer.setVolume(volume);
  return renderer.render(settings);
}

cv::Point2d pixelOfVoxel(const View& view, glm::dvec3 voxel) {
  const glm::dvec4 clip = view.clipFromVoxel() * glm::dvec4(voxel, 1.0);
  return {(clip.x / clip.w + 1) * 0.5 * view.viewport.x - 0.5,
          (1 - clip.y / clip.w) * 0.5 * view.viewport.y - 0.5};
}

double pixelsPerVoxel(const View& view) {
  const double worldPerVoxel = view.worldFromVoxel[0][0];
  const double pixelsPerWorld = view.viewport.y / (2.0 * view.halfExtent.y);
  return worldPerVoxel * pixelsPerWorld;
}

}  // namespace vsil::test
