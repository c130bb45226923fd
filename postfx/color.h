#pragma once
// Colours given on the command line: a name (black, white, red, green, blue, yellow, cyan,
// magenta, grey/gray, orange, transparent) or hex #rgb, #rrggbb, #rrggbbaa.
#include <string>

#include <opencv2/core.hpp>

namespace vsil {

struct Rgba {
  int r = 0, g = 0, b = 0, a = 255;
  bool operator==(const Rgba&) const = default;
  cv::Vec4b bgra() const { return cv::Vec4b(b, g, r, a); }
  cv::Vec3b bgr() const { return cv::Vec3b(b, g, r); }
};

// Throws InputError "<flagName>: ..." naming the text and the accepted forms.
Rgba parseColor(const std::string& text, const std::string& flagName);

}  // namespace vsil
