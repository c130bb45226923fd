#pragma once
// Composition of an illustration. For techniques that return pixel states (silhouette,
// rightangle): broadened lines in the line colour over the fill of the Filled pixels (none, a
// flat colour, that colour shaded by the diffuse shade, or the tone-shaded colour the technique
// computed, FrameBuffers::tone) over the background. For techniques that return colour
// (FrameBuffers::color, premultiplied): that colour over the background.
// The result is 8-bit BGRA (BGR when every colour is opaque), ready for writePng.
#include <optional>

#include <opencv2/core.hpp>

#include "core/color.h"
#include "core/frame.h"
#include "postfx/gaussian_fft.h"
#include "postfx/width_law.h"

namespace vsil {

// What Filled pixels show: nothing; the fill colour; the fill colour times the headlight shade
// |n·v| (FrameBuffers::shade); the fill colour tone-shaded and distance-blended by the technique
// (FrameBuffers::tone; the render must ask for it, RenderSettings::toneFill).
enum class FillMode { None, Flat, Shaded, Tone };
const char* fillModeName(FillMode fill);

struct PostfxOptions {
  WidthLaw width = WidthLaw::fixed(3);
  Rgba lineColor{0, 0, 0, 255};
  // Unset: the technique's choice (RenderResult::background), else white.
  std::optional<Rgba> background;
  FillMode fill = FillMode::None;
  Rgba fillColor{200, 200, 200, 255};
};

// `lines` is the broadened line mask (broaden.h); pass an empty Mat to broaden here.
cv::Mat composeIllustration(const FrameBuffers& frame, const PostfxOptions& options,
                            FftGaussianBlur& blur, const cv::Mat1b& lines = {});

}  // namespace vsil
