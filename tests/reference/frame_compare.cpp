#include "frame_compare.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/illustration.h"
#include "gl_harness.h"

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

cv::Mat3f objectColours(const FrameBuffers& frame) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  if (!frame.tone.empty()) {
    cv::Mat3f colours(frame.tone.size(), cv::Vec3f(nan, nan, nan));
    for (int y = 0; y < colours.rows; ++y) {
      for (int x = 0; x < colours.cols; ++x) {
        if (PixelState(frame.state(y, x)) == PixelState::Filled) colours(y, x) = frame.tone(y, x);
      }
    }
    return colours;
  }
  cv::Mat3f colours(frame.color.size(), cv::Vec3f(nan, nan, nan));
  for (int y = 0; y < colours.rows; ++y) {
    for (int x = 0; x < colours.cols; ++x) {
      const cv::Vec4f c = frame.color(y, x);
      if (c[3] > 0.5f) colours(y, x) = cv::Vec3f(c[0], c[1], c[2]) / c[3];
    }
  }
  return colours;
}

ToneSides toneSides(const cv::Mat3f& colours, glm::dvec3 light) {
  ToneSides sides;
  glm::dvec2 centre(0.0);
  for (int y = 0; y < colours.rows; ++y) {
    for (int x = 0; x < colours.cols; ++x) {
      if (std::isnan(colours(y, x)[0])) continue;
      centre += glm::dvec2(x + 0.5, y + 0.5);
      ++sides.object;
    }
  }
  if (sides.object == 0) return sides;
  centre /= double(sides.object);
  const double radius = std::sqrt(sides.object / std::numbers::pi);
  for (int y = 0; y < colours.rows; ++y) {
    for (int x = 0; x < colours.cols; ++x) {
      const cv::Vec3f c = colours(y, x);
      if (std::isnan(c[0])) continue;
      const glm::dvec2 onDisc = glm::dvec2(x + 0.5 - centre.x, centre.y - (y + 0.5)) / radius;
      const glm::dvec3 n(onDisc, std::sqrt(std::max(0.0, 1.0 - glm::dot(onDisc, onDisc))));
      const double nl = glm::dot(glm::normalize(n), light);
      if (nl > 0.25) {
        ++sides.lit;
        sides.litWarm += c[0] > c[2];
      } else if (nl < -0.25) {
        ++sides.unlit;
        sides.unlitCool += c[2] > c[0];
      }
      const float brightest = std::max({c[0], c[1], c[2]});
      sides.atWhite += brightest >= 254.5f / 255.0f;
      sides.brightest = std::max(sides.brightest, brightest);
    }
  }
  return sides;
}

void expectIvoryToneWarmWhereLitCoolWhereNotAndNotClipped(const Volume& volume,
                                                          RenderSettings settings) {
  settings.options["light"] = std::vector<std::string>{"0,90"};  // straight above
  const RenderResult above = renderOnce(volume, settings);
  const ToneSides sides = toneSides(objectColours(above.frame), {0, 1, 0});
  EXPECT_GT(sides.lit, 300);
  EXPECT_EQ(sides.litWarm, sides.lit) << "R > B wherever n·L > 0.25";
  EXPECT_GT(sides.unlit, 300);
  EXPECT_EQ(sides.unlitCool, sides.unlit) << "B > R wherever n·L < -0.25";
  // The default light (0,60), as the presets have it: its highlight faces the viewer.
  settings.options.erase("light");
  const RenderResult lit = renderOnce(volume, settings);
  const ToneSides clip = toneSides(objectColours(lit.frame), Light{}.directionEye());
  std::cout << "[ info ] " << clip.atWhite << " of " << clip.object
            << " pixels with a channel at 255, brightest " << clip.brightest << "\n";
  EXPECT_GT(clip.object, 1000);
  EXPECT_LT(clip.atWhite, clip.object / 100) << "under 1 % at 255";
  EXPECT_GT(clip.brightest, 0.9f) << "the highlight nearly white";
}

OptionValues isoOptions(const TechniqueInfo& technique, double iso) {
  OptionValues options;
  if (technique.usesIso()) options["iso"] = iso;
  return options;
}

}  // namespace vsil::test
