#include "slicing/techniques/mip/mip_options.h"

#include <variant>

#include "core/error.h"
#include "core/number_pair.h"
#include "slicing/illustration_options.h"
#include "slicing/techniques/mip/colour_sphere.h"

namespace vsil {

OptionSpec windowOption() {
  OptionSpec spec = OptionSpec::text(
      "window", "LO,HI in data units mapped to black..white; values at or below LO show nothing");
  spec.defaultNote =
      "from the histogram: Otsu's threshold (the default --iso) to the 99.5th percentile of the "
      "values above it";
  return spec;
}

IntensityWindow intensityWindow(const OptionReader& options) {
  const std::string& text = options.text("window");
  if (text.empty()) {
    const DerivedDefaults& derived = options.derived();
    return {float(derived.iso), float(derived.windowHigh)};
  }
  const glm::dvec2 pair = parseNumberPair("--window", text);
  return {float(pair.x), float(pair.y)};
}

std::string windowText(const IntensityWindow& window) {
  return formatNumberList({double(window.low), double(window.high)});
}

std::optional<TransferFunction> mipTransferFunction(const OptionReader& options) {
  const std::string& path = options.text("tf");
  if (path.empty()) return std::nullopt;
  return transferFunctionOption(path, options.derived());
}

void checkWindowOrTf(const OptionValues& given) {
  const std::string* tf = givenText(given, "tf");
  if (tf && !tf->empty()) checkTransferFunctionOption(*tf);  // InputError naming the file
  const std::string* text = givenText(given, "window");
  if (!text || text->empty()) return;
  const glm::dvec2 pair = parseNumberPair("--window", *text);
  requireSinglePrecision("--window: '" + *text + "'", {pair.x, pair.y});
  if (!(pair.x < pair.y)) {
    throwInputError("--window", "'" + *text + "' needs LO < HI");
  }
  if (tf && !tf->empty()) {
    throwInputError("--tf",
                    "give --window or --tf, not both (the transfer function replaces the "
                    "window's grey ramp)");
  }
}

OptionSpec lmipThresholdOption() {
  OptionSpec spec = OptionSpec::number(
      "lmip-threshold", 0,
      "LMIP shows the first local maximum at or above this value along each ray (data units)");
  spec.defaultValue.reset();
  // Resolved by lmipThreshold: the window's low end, which is the volume's iso (Otsu) unless
  // --window is given; the derived value keeps the reader's number defined.
  spec.derived = OptionSpec::Derived::VolumeIso;
  spec.defaultNote = "the window's low end (given or default)";
  return spec;
}

float lmipThreshold(const OptionReader& options) {
  if (options.given("lmip-threshold")) return float(options.number("lmip-threshold"));
  return intensityWindow(options).low;
}

std::vector<OptionSpec> demipOptions() {
  OptionSpec eps = OptionSpec::number(
      "material-eps", 0,
      "the same material: samples within this of the pixel's maximum (data units)");
  eps.above(0);
  eps.defaultValue.reset();
  eps.derived = OptionSpec::Derived::RangeFraction;
  eps.rangeFraction = 0.05;
  eps.defaultNote = "5 % of the value range";
  OptionSpec map =
      OptionSpec::text("sphere-map",
                       "colour sphere: red-blue, green-red, green-blue, or an equirectangular "
                       "FILE.png (its centre toward the viewer)");
  map.defaultValue = std::string("red-blue");
  OptionSpec rotate =
      OptionSpec::text("sphere-rotate", "AZ,EL degrees: turns the colour sphere (180,0 swaps)");
  rotate.defaultValue = std::string("0,0");
  return {
      windowOption(),
      transferFunctionOption(),
      eps,
      OptionSpec::number("depth-weight", 0.15,
                         "d_w in color = MIP*(1 - d_w) + 2*d_w*(1 - depth); 0 is plain MIP")
          .atLeast(0)
          .atMost(1),
      OptionSpec::choice("depth-mode", "exact", {"exact", "steps", "entry-plus-steps"},
                         "depth of the first hit: exact eye distance, ray steps inside the box, "
                         "or the box entry's window depth plus the steps (paper Fig. 3)"),
      OptionSpec::number("sphere-weight", 0.0, "weight of the colour sphere (0 = off)")
          .atLeast(0)
          .atMost(1),
      map,
      rotate,
      OptionSpec::choice("sphere-frame", "view", {"view", "volume"},
                         "the colour sphere fixed to the view, or to the volume"),
      OptionSpec::flag("legend", "draw the colour sphere, as used, in the bottom-right corner"),
  };
}

void checkDemipValues(const OptionValues& given) {
  checkWindowOrTf(given);
  if (const std::string* name = givenText(given, "sphere-map")) checkSphereMap(*name);
  if (const std::string* text = givenText(given, "sphere-rotate")) {
    const glm::dvec2 angles = parseNumberPair("--sphere-rotate", *text);
    requireSinglePrecision("--sphere-rotate: '" + *text + "'", {angles.x, angles.y});
  }
}

DepthMode depthMode(const OptionReader& options) {
  const std::string& mode = options.text("depth-mode");
  if (mode == "steps") return DepthMode::Steps;
  if (mode == "entry-plus-steps") return DepthMode::EntryPlusSteps;
  return DepthMode::Exact;
}

}  // namespace vsil
