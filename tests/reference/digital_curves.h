#pragma once
// One-pixel digital curves made on the CPU the way the silhouette technique makes them:
// a pixel is filled when its centre (x, y) (pixel indices, centres at integers here) lies inside
// an analytic shape, and it is a silhouette pixel when it is filled and one of its 8 neighbours
// is not. Neighbours outside the image are evaluated from the shape too, so the image border
// makes no outline of its own.
#include <functional>
#include <vector>

#include <opencv2/core.hpp>

#include "core/frame.h"

namespace vsil::test {

using InsideTest = std::function<bool(double x, double y)>;

InsideTest discShape(cv::Point2d centre, double radius);
// The half-plane on the left of a line through `point` running at angle `angleDeg` (degrees,
// from +x towards +y): its outline is a straight line at that angle.
InsideTest halfPlaneShape(cv::Point2d point, double angleDeg);

cv::Mat1b filledPixels(cv::Size size, const InsideTest& inside);
// 255 on the silhouette pixels, 0 elsewhere.
cv::Mat1b silhouettePixels(cv::Size size, const InsideTest& inside);

// A frame of discs, each with its own normalized depth (constant over the disc, as a sphere's
// silhouette is in an orthographic view); later discs are drawn behind earlier ones.
struct DepthDisc {
  cv::Point2d centre;
  double radius;
  double depth;
};
FrameBuffers discsFrame(cv::Size size, const std::vector<DepthDisc>& discs);

// Width of a band (non-zero pixels) around a circle centred at `centre` whose inner hole holds
// every pixel closer than `holeRadius` to the centre: outer minus inner radius of the band, from
// the areas (band area divided by the length of its centre curve). Only pixels closer than
// `outerLimit` count.
double ringBandWidth(const cv::Mat1b& band, cv::Point2d centre, double holeRadius,
                     double outerLimit);

// Width of a band along a straight line through `point` at `angleDeg`: band area within
// |along| <= halfLength and |across| <= halfAcross, divided by 2·halfLength.
double straightBandWidth(const cv::Mat1b& band, cv::Point2d point, double angleDeg,
                         double halfLength, double halfAcross);

}  // namespace vsil::test
