#include "postfx/compose.h"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

#include "postfx/broaden.h"

namespace vsil {

namespace {

// Premultiplied RGBA in [0, 1] over the background colour: c + (1 − α)·background.
cv::Mat composeColorOverBackground(const cv::Mat4f& color, const Rgba& background) {
  const bool opaque = background.a == 255;
  const cv::Vec4b bg = background.bgra();
  const double bgAlpha = background.a / 255.0;
  cv::Mat4b image(color.size());
  for (int y = 0; y < image.rows; ++y) {
    const cv::Vec4f* in = color[y];
    cv::Vec4b* out = image[y];
    for (int x = 0; x < image.cols; ++x) {
      const double alpha = std::clamp(double(in[x][3]), 0.0, 1.0);
      // Colour premultiplied by the result's alpha, then un-premultiplied for the PNG.
      const double outAlpha = alpha + (1.0 - alpha) * bgAlpha;
      for (int c = 0; c < 3; ++c) {
        const double rgb = in[x][2 - c] + (1.0 - alpha) * bgAlpha * (bg[c] / 255.0);  // BGR order
        const double straight = outAlpha > 0 ? rgb / outAlpha : 0.0;
        out[x][c] = cv::saturate_cast<std::uint8_t>(std::lround(straight * 255.0));
      }
      out[x][3] = cv::saturate_cast<std::uint8_t>(std::lround(outAlpha * 255.0));
    }
  }
  if (!opaque) return image;
  cv::Mat3b bgr;
  cv::cvtColor(image, bgr, cv::COLOR_BGRA2BGR);
  return bgr;
}

// Straight-alpha `top` over `bottom` (BGRA, 8 bits): an opaque top or a transparent bottom
// gives `top` exactly (a line over the transparent background keeps its own alpha).
cv::Vec4b over(const cv::Vec4b& top, const cv::Vec4b& bottom) {
  if (top[3] == 255 || bottom[3] == 0) return top;
  const double a = top[3] / 255.0, b = bottom[3] / 255.0 * (1.0 - a);
  const double outAlpha = a + b;
  cv::Vec4b out;
  for (int c = 0; c < 3; ++c) {
    out[c] = cv::saturate_cast<std::uint8_t>(std::lround((top[c] * a + bottom[c] * b) / outAlpha));
  }
  out[3] = cv::saturate_cast<std::uint8_t>(std::lround(outAlpha * 255.0));
  return out;
}

}  // namespace

const char* fillModeName(FillMode fill) {
  static const char* const names[] = {"none", "flat", "shaded", "tone"};
  return names[int(fill)];
}

cv::Mat composeIllustration(const FrameBuffers& frame, const PostfxOptions& options,
                            FftGaussianBlur& blur, const cv::Mat1b& lines) {
  const Rgba background = options.background.value_or(kDefaultBackground);
  if (frame.state.empty()) return composeColorOverBackground(frame.color, background);
  const cv::Mat1b band = lines.empty() ? broadenSilhouettes(frame, options.width, blur) : lines;
  // Lines and fills with an alpha are composited over what is under them (the fill over the
  // background, a line over both), as the volume's colours are.
  const bool opaque = background.a == 255;
  const cv::Vec4b lineColor = options.lineColor.bgra(), fillColor = options.fillColor.bgra();
  const bool shaded = options.fill == FillMode::Shaded && !frame.shade.empty();
  const bool toned = options.fill == FillMode::Tone && !frame.tone.empty();
  cv::Mat4b image(frame.state.size(), background.bgra());
  for (int y = 0; y < image.rows; ++y) {
    cv::Vec4b* out = image[y];
    const std::uint8_t* inBand = band[y];
    const std::uint8_t* state = frame.state[y];
    for (int x = 0; x < image.cols; ++x) {
      if (options.fill == FillMode::None || state[x] == std::uint8_t(PixelState::Empty)) {
        if (inBand[x]) out[x] = over(lineColor, out[x]);
        continue;
      }
      cv::Vec4b fill = fillColor;
      if (shaded) {
        const float shade = frame.shade(y, x);
        const double k = std::isnan(shade) ? 1.0 : std::clamp(double(shade), 0.0, 1.0);
        for (int c = 0; c < 3; ++c) fill[c] = cv::saturate_cast<std::uint8_t>(fill[c] * k);
      }
      if (toned && !std::isnan(frame.tone(y, x)[0])) {
        const cv::Vec3f& rgb = frame.tone(y, x);
        for (int c = 0; c < 3; ++c) {  // BGR order
          fill[c] = cv::saturate_cast<std::uint8_t>(std::lround(rgb[2 - c] * 255.0));
        }
      }
      out[x] = over(fill, out[x]);
      if (inBand[x]) out[x] = over(lineColor, out[x]);
    }
  }
  if (!opaque) return image;
  cv::Mat3b bgr;
  cv::cvtColor(image, bgr, cv::COLOR_BGRA2BGR);
  return bgr;
}

}  // namespace vsil
