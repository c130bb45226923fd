#pragma once
// Helpers for the postfx GL suite: orthographic renders of analytic volumes, and where their
// silhouettes lie in the image, computed from the view (not from the rendered pixels).
#include <glm/glm.hpp>
#include <opencv2/core.hpp>

#include "analytic_volumes.h"
#include "slicing/renderer.h"

namespace vsil::test {

// One orthographic silhouette frame of `volume`, iso 0.5, through the suite's shared context.
RenderResult renderOrthographic(const Volume& volume, glm::ivec2 size, double azimuthDeg = 0,
                                double elevationDeg = 0);

// Pixel coordinates with centres at integers (the convention of digital_curves.h) of a voxel
// point: the View's pixel coordinates (centres at +0.5) minus one half.
cv::Point2d pixelOfVoxel(const View& view, glm::dvec3 voxel);
// Pixels per voxel of an orthographic view (spacing 1).
double pixelsPerVoxel(const View& view);

}  // namespace vsil::test
