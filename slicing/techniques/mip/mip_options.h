#pragma once
// The options of mip, lmip and demip, declared once here (a flag two techniques share must mean
// the same), and the text values they parse themselves.
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/camera.h"
#include "core/options.h"
#include "core/transfer_function.h"
#include "core/volume.h"

namespace vsil {

// --window LO,HI: data values mapped linearly to grey 0..1. A pixel shows something only where
// its value exceeds LO, so bricks whose maximum is at most LO cannot change a pixel.
struct IntensityWindow {
  float low = 0.0f;
  float high = 1.0f;
};
OptionSpec windowOption();
// The given window, else the volume's default window (core/volume.h derivedDefaults: Otsu's
// threshold to the 99.5th percentile above it), so that air and noise show as background.
IntensityWindow intensityWindow(const OptionReader& options);
// The window as the metadata records it ("LO,HI"), given or derived.
std::string windowText(const IntensityWindow& window);

// --tf FILE instead of the window (illustration_options.h transferFunctionOption, the file
// illustrate reads): each pixel's value takes the function's colour and opacity (premultiplied;
// mip_finish.frag), so a pixel shows something only where the opacity at its value is above 0.
std::optional<TransferFunction> mipTransferFunction(const OptionReader& options);  // if given

// --window LO < HI, a readable --tf, and not both.
void checkWindowOrTf(const OptionValues& given);

OptionSpec lmipThresholdOption();
// The given --lmip-threshold, else the window's low end (given or default; with --tf the default
// window's, Otsu's threshold): the first local maximum LMIP shows is one the window shows.
float lmipThreshold(const OptionReader& options);

// demip's own options: material tolerance, depth weighting, colour sphere (colour_sphere.h),
// legend.
std::vector<OptionSpec> demipOptions();
void checkDemipValues(const OptionValues& given);

// Depth estimates of the paper's Figure 3 (--depth-mode).
enum class DepthMode { Exact, Steps, EntryPlusSteps };
DepthMode depthMode(const OptionReader& options);

}  // namespace vsil
