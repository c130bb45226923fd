#pragma once
// --legend: the colour sphere drawn as an inset in the bottom-right corner of a demip frame, so
// that a reader can decode the colours: each pixel of a disc shows the map's colour at the
// point of the sphere's near half seen there, rotated as the render used it (sphereFrontEye),
// and a cross marks the view direction (the disc's centre faces the viewer).
#include <glm/glm.hpp>
#include <opencv2/core.hpp>

#include "slicing/techniques/mip/mip_options.h"

namespace vsil {

// Draws into `colour` (premultiplied RGBA, top-left origin), opaque.
void drawSphereLegend(cv::Mat4f& colour, const SphereMap& map, glm::vec3 sphereFrontEye);

}  // namespace vsil
