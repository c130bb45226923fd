#pragma once
// --legend: the colour sphere drawn as an inset in the bottom-right corner of a demip frame, so
// that a reader can decode the colours: each pixel of a disc shows the map's colour (a built-in
// or a PNG, colour_sphere.h) at the point of the sphere's near half seen there, turned as the
// render used it (sphereFrameEye), and a cross marks the view direction (the disc's centre
// faces the viewer).
#include <glm/glm.hpp>
#include <opencv2/core.hpp>

#include "slicing/techniques/mip/colour_sphere.h"

namespace vsil {

// Draws into `colour` (premultiplied RGBA, top-left origin), opaque.
// `sphereFrameEye`: the sphere's frame in eye space (colour_sphere.h).
void drawSphereLegend(cv::Mat4f& colour, const ColourSphere& sphere,
                      const glm::mat3& sphereFrameEye);

}  // namespace vsil
