#pragma once
// What a technique hands back after a frame: CPU images in pixel space (origin top-left).
#include <cstdint>

#include <opencv2/core.hpp>

namespace vsil {

// Nagy–Klein pixel states. The numeric values are shared with the GLSL sources
// (slicing/shaders/common.glsl); a GL test checks that they agree.
enum class PixelState : std::uint8_t { Empty = 0, Filled = 1, Contour = 2, Silhouette = 3 };

// Grey levels of the state image written by `vsil render --state-out`.
inline std::uint8_t stateGrey(PixelState state) {
  return std::uint8_t(85 * int(state));
}

struct FrameBuffers {
  cv::Mat1b state;  // PixelState per pixel
  // Normalized depth d in [0, 1] (see View::normalizedDepth) of the surface a pixel shows:
  // for Silhouette pixels where the silhouette lies, for Filled pixels the first hit.
  // NaN where the pixel shows nothing.
  cv::Mat1f depth;
  // Diffuse shade in [0, 1] of the first iso-surface hit (Filled pixels), NaN elsewhere.
  cv::Mat1f shade;
  // Tone-shaded colour of the first iso-surface hit (Filled pixels), straight RGB (red first),
  // not clamped; NaN elsewhere. Only when the render asked for it (RenderSettings::toneFill,
  // `--fill tone`); empty otherwise.
  cv::Mat3f tone;
  // Techniques that composite colour (illustrate, mip, semantic) fill this, premultiplied RGBA.
  cv::Mat4f color;

  int width() const { return state.cols; }
  int height() const { return state.rows; }
};

}  // namespace vsil
