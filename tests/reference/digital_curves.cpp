#include "digital_curves.h"

#include <cmath>
#include <numbers>

namespace vsil::test {

InsideTest discShape(cv::Point2d centre, double radius) {
  return [=](double x, double y) {
    return (x - centre.x) * (x - centre.x) + (y - centre.y) * (y - centre.y) < radius * radius;
  };
}

InsideTest halfPlaneShape(cv::Point2d point, double angleDeg) {
  const double a = angleDeg * std::numbers::pi / 180.0;
  const double nx = -std::sin(a), ny = std::cos(a);  // normal towards the inside
  return [=](double x, double y) { return (x - point.x) * nx + (y - point.y) * ny > 0; };
}

cv::Mat1b filledPixels(cv::Size size, const InsideTest& inside) {
  cv::Mat1b filled(size, 0);
  for (int y = 0; y < size.height; ++y) {
    for (int x = 0; x < size.width; ++x) filled(y, x) = inside(x, y) ? 255 : 0;
  }
  return filled;
}

cv::Mat1b silhouettePixels(cv::Size size, const InsideTest& inside) {
  cv::Mat1b outline(size, 0);
  for (int y = 0; y < size.height; ++y) {
    for (int x = 0; x < size.width; ++x) {
      if (!inside(x, y)) continue;
      bool edge = false;
      for (int dy = -1; dy <= 1 && !edge; ++dy) {
        for (int dx = -1; dx <= 1 && !edge; ++dx) edge = !inside(x + dx, y + dy);
      }
      outline(y, x) = edge ? 255 : 0;
    }
  }
  return outline;
}

FrameBuffers discsFrame(cv::Size size, const std::vector<DepthDisc>& discs) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  FrameBuffers frame;
  frame.state = cv::Mat1b(size, std::uint8_t(PixelState::Empty));
  frame.depth = cv::Mat1f(size, nan);
  frame.shade = cv::Mat1f(size, nan);
  // Back to front, so the nearest disc (first in the list) ends on top.
  for (auto disc = discs.rbegin(); disc != discs.rend(); ++disc) {
    const auto inside = discShape(disc->centre, disc->radius);
    const cv::Mat1b filled = filledPixels(size, inside);
    const cv::Mat1b outline = silhouettePixels(size, inside);
    for (int y = 0; y < size.height; ++y) {
      for (int x = 0; x < size.width; ++x) {
        if (!filled(y, x)) continue;
        frame.state(y, x) =
            std::uint8_t(outline(y, x) ? PixelState::Silhouette : PixelState::Filled);
        frame.depth(y, x) = float(disc->depth);
        const double r = std::hypot(x - disc->centre.x, y - disc->centre.y) / disc->radius;
        frame.shade(y, x) = float(std::sqrt(std::max(0.0, 1.0 - r * r)));
      }
    }
  }
  return frame;
}

double ringBandWidth(const cv::Mat1b& band, cv::Point2d centre, double holeRadius,
                     double outerLimit) {
  double bandArea = 0, holeArea = 0;
  for (int y = 0; y < band.rows; ++y) {
    for (int x = 0; x < band.cols; ++x) {
      const double r = std::hypot(x - centre.x, y - centre.y);
      if (r >= outerLimit) continue;
      if (band(y, x)) {
        bandArea += 1;
      } else if (r < holeRadius) {
        holeArea += 1;
      }
    }
  }
  const double outer = std::sqrt((bandArea + holeArea) / std::numbers::pi);
  const double inner = std::sqrt(holeArea / std::numbers::pi);
  return outer - inner;
}

double straightBandWidth(const cv::Mat1b& band, cv::Point2d point, double angleDeg,
                         double halfLength, double halfAcross) {
  const double a = angleDeg * std::numbers::pi / 180.0;
  const double tx = std::cos(a), ty = std::sin(a);
  double area = 0;
  for (int y = 0; y < band.rows; ++y) {
    for (int x = 0; x < band.cols; ++x) {
      if (!band(y, x)) continue;
      const double along = (x - point.x) * tx + (y - point.y) * ty;
      const double across = -(x - point.x) * ty + (y - point.y) * tx;
      if (std::abs(along) <= halfLength && std::abs(across) <= halfAcross) area += 1;
    }
  }
  return area / (2 * halfLength);
}

}  // namespace vsil::test
