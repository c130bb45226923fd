#pragma once
// Colours given on the command line and in style files: a name (black, white, red, green,
// blue, yellow, cyan, magenta, grey/gray, orange, navy, ivory, transparent) or hex #rgb,
// #rrggbb, #rrggbbaa. One parser for composition (postfx) and the techniques that blend
// towards a colour (illustrate's distance colour blending towards the background).
#include <string>

#include <glm/glm.hpp>
#include <opencv2/core.hpp>

namespace vsil {

struct Rgba {
  int r = 0, g = 0, b = 0, a = 255;
  bool operator==(const Rgba&) const = default;
  cv::Vec4b bgra() const { return cv::Vec4b(b, g, r, a); }
  cv::Vec3b bgr() const { return cv::Vec3b(b, g, r); }
  // Straight (not premultiplied) channels in [0, 1], for shaders.
  glm::vec3 rgb01() const { return glm::vec3(r, g, b) / 255.0f; }
  // "#rrggbbaa", for metadata.
  std::string hex() const;
};

// What illustrations are composed over when nobody chose a colour.
inline constexpr Rgba kDefaultBackground{255, 255, 255, 255};

// Throws InputError "<flagName>: ..." naming the text and the accepted forms.
Rgba parseColor(const std::string& text, const std::string& flagName);
// A colour whose alpha nothing reads (a sample's colour, the line colour measure-width looks
// for): one with alpha below ff (transparent, #rrggbbaa) is refused, "<flagName>: ... <why>",
// not silently taken as opaque.
Rgba parseOpaqueColor(const std::string& text, const std::string& flagName, const std::string& why);

}  // namespace vsil
