#include "frame_compare.h"

#include <algorithm>
#include <cmath>

namespace vsil::test {

namespace {

bool sameFloat(float a, float b) {
  return (std::isnan(a) && std::isnan(b)) || a == b;
}

bool sameAt(const cv::Mat& a, const cv::Mat& b, int y, int x) {
  if (a.empty() && b.empty()) return true;
  if (a.size() != b.size() || a.type() != b.type()) return false;
  switch (a.type()) {
    case CV_8UC1:
      return a.at<std::uint8_t>(y, x) == b.at<std::uint8_t>(y, x);
    case CV_32FC1:
      return sameFloat(a.at<float>(y, x), b.at<float>(y, x));
    case CV_32FC3: {
      const auto& p = a.at<cv::Vec3f>(y, x);
      const auto& q = b.at<cv::Vec3f>(y, x);
      for (int c = 0; c < 3; ++c) {
        if (!sameFloat(p[c], q[c])) return false;
      }
      return true;
    }
    case CV_32FC4: {
      const auto& p = a.at<cv::Vec4f>(y, x);
      const auto& q = b.at<cv::Vec4f>(y, x);
      for (int c = 0; c < 4; ++c) {
        if (!sameFloat(p[c], q[c])) return false;
      }
      return true;
    }
  }
  return false;
}

}  // namespace

int differingPixels(const FrameBuffers& a, const FrameBuffers& b) {
  const cv::Size size = !a.state.empty() ? a.state.size() : a.color.size();
  int differing = 0;
  for (int y = 0; y < size.height; ++y) {
    for (int x = 0; x < size.width; ++x) {
      const bool same = sameAt(a.state, b.state, y, x) && sameAt(a.depth, b.depth, y, x) &&
                        sameAt(a.shade, b.shade, y, x) && sameAt(a.tone, b.tone, y, x) &&
                        sameAt(a.color, b.color, y, x);
      differing += same ? 0 : 1;
    }
  }
  return differing;
}

double maxChannelDifference(const cv::Mat4f& a, const cv::Mat4f& b) {
  cv::Mat diff;
  cv::absdiff(a, b, diff);
  double largest = 0;
  cv::minMaxLoc(diff.reshape(1), nullptr, &largest);
  return largest;
}

double maxChannelDifference(const cv::Mat4f& a, const cv::Mat4f& b, int y, int x) {
  double largest = 0;
  for (int k = 0; k < 4; ++k)
    largest = std::max(largest, double(std::abs(a(y, x)[k] - b(y, x)[k])));
  return largest;
}

int shownPixels(const FrameBuffers& frame) {
  int shown = 0;
  if (!frame.state.empty()) {
    for (auto it = frame.state.begin(); it != frame.state.end(); ++it) {
      shown += *it != std::uint8_t(PixelState::Empty);
    }
    return shown;
  }
  for (auto it = frame.color.begin(); it != frame.color.end(); ++it) shown += (*it)[3] > 0.0f;
  return shown;
}

OptionValues isoOptions(const TechniqueInfo& technique, double iso) {
  OptionValues options;
  if (technique.usesIso()) options["iso"] = iso;
  return options;
}

}  // namespace vsil::test
