#include "slicing/techniques/mip/sphere_legend.h"

#include <algorithm>
#include <cmath>

namespace vsil {

void drawSphereLegend(cv::Mat4f& colour, const ColourSphere& sphere,
                      const glm::mat3& sphereFrameEye) {
  const glm::mat3 sphereFromEye = glm::transpose(sphereFrameEye);
  const int side = std::min(colour.cols, colour.rows);
  const int radius = std::max(6, side / 10);
  const int margin = std::max(2, radius / 4);
  const cv::Point centre(colour.cols - margin - radius - 1, colour.rows - margin - radius - 1);
  const int crossArm = std::max(2, radius / 4);
  for (int dy = -radius; dy <= radius; ++dy) {
    for (int dx = -radius; dx <= radius; ++dx) {
      const int x = centre.x + dx, y = centre.y + dy;
      if (x < 0 || y < 0 || x >= colour.cols || y >= colour.rows) continue;
      const float u = (dx + 0.5f) / radius, v = -(dy + 0.5f) / radius;  // eye x right, y up
      const float r2 = u * u + v * v;
      if (r2 > 1.0f) continue;
      const glm::vec3 normal(u, v, std::sqrt(1.0f - r2));  // the near half, facing +z eye
      glm::vec3 c = sphere.colourAt(sphereFromEye * normal);
      const bool onCross = (dx == 0 || dy == 0) && std::abs(dx + dy) <= crossArm;
      if (onCross) c = glm::vec3(1.0f);
      colour(y, x) = cv::Vec4f(c.r, c.g, c.b, 1.0f);
    }
  }
}

}  // namespace vsil
