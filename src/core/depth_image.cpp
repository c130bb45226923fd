#include "core/depth_image.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.h"

namespace vsil {

namespace {
constexpr double kDepthSteps = 65534.0;  // 0 is reserved for "no depth"
}

cv::Mat1w encodeDepthImage(const cv::Mat1f& depth) {
  cv::Mat1w image(depth.size(), 0);
  for (int y = 0; y < depth.rows; ++y) {
    for (int x = 0; x < depth.cols; ++x) {
      const float d = depth(y, x);
      if (std::isnan(d)) continue;
      image(y, x) = std::uint16_t(1 + std::lround(std::clamp(double(d), 0.0, 1.0) * kDepthSteps));
    }
  }
  return image;
}

cv::Mat1f decodeDepthImage(const cv::Mat& image, const std::filesystem::path& path) {
  if (image.channels() != 1 || (image.depth() != CV_16U && image.depth() != CV_32F)) {
    throwInputError(path.string(),
                    "is not a depth image (expected 16-bit grey, as render --depth-out writes)");
  }
  if (image.depth() == CV_32F) return image.clone();
  cv::Mat1f depth(image.size(), std::numeric_limits<float>::quiet_NaN());
  for (int y = 0; y < image.rows; ++y) {
    for (int x = 0; x < image.cols; ++x) {
      const std::uint16_t v = image.at<std::uint16_t>(y, x);
      if (v != 0) depth(y, x) = float((v - 1) / kDepthSteps);
    }
  }
  return depth;
}

}  // namespace vsil
