#include "slicing/illustration_options.h"

#include <algorithm>

#include "core/error.h"
#include "core/transfer_function.h"

namespace vsil {

std::string lightCountDefine(const Illustration& illustration) {
  return "LIGHT_COUNT " + std::to_string(illustration.lights.size());
}

namespace {

const std::string& textOf(const OptionValue& value) {
  return std::get<std::string>(value);
}

std::string joinedNames(const std::vector<std::string>& names) {
  std::string text;
  for (const auto& name : names) text += (text.empty() ? "" : ", ") + name;
  return text;
}

bool declares(const std::vector<OptionSpec>& declared, const std::string& name) {
  return std::any_of(declared.begin(), declared.end(),
                     [&](const OptionSpec& spec) { return spec.name == name; });
}

}  // namespace

OptionSpec parameterOption(std::vector<std::string> allowed, std::string owner) {
  return OptionSpec::list("param",
                          "illustration parameters NAME=VALUE,... by the paper's names (k_gc, "
                          "k_ss, k_ta, ...; README, volume illustration; with --fill tone the "
                          "tone, distance and lighting ones); repeatable")
      .validatedBy(
          [allowed = std::move(allowed), owner = std::move(owner)](const OptionValue& value) {
            ParameterValues ignored;
            for (const auto& text : std::get<std::vector<std::string>>(value)) {
              parseParameterList(text, "--param", allowed, owner, ignored);
            }
          });
}

OptionSpec lightOption() {
  return OptionSpec::list("light",
                          "a directional light AZ,EL in degrees relative to the view (0,0 shines "
                          "from the viewer, 0,90 from above); repeatable; default one light at "
                          "0,60, above and slightly toward the viewer")
      .validatedBy([](const OptionValue& value) {
        const auto& lights = std::get<std::vector<std::string>>(value);
        if (lights.size() > kMaxLights) {
          throwInputError("--light", "at most " + std::to_string(kMaxLights) + " lights (got " +
                                         std::to_string(lights.size()) + ")");
        }
        for (const auto& text : lights) parseLight(text, "--light");
      });
}

OptionSpec effectsOption() {
  return OptionSpec::text("effects",
                          "illustration effects, comma-separated: boundary, silhouette, fading, "
                          "sketch, distance, halo, tone (none: the plain lit composite)")
      .validatedBy([](const OptionValue& value) { parseEffects(textOf(value), "--effects"); });
}

OptionSpec styleOption() {
  OptionSpec spec =
      OptionSpec::text(
          "style",
          "an illustration style: a preset name (README) or a .json file of effects, "
          "parameters, transfer function, colours and lights (or that JSON itself); flags "
          "beside it win")
          .validatedBy([](const OptionValue& value) {
            const std::string& text = textOf(value);
            if (text.empty() || (isStyleFile(text) && !isInlineSource(text))) return;
            const auto names = stylePresetNames();
            if (std::find(names.begin(), names.end(), text) == names.end()) loadStyle(text);
          });
  return spec;
}

OptionSpec transferFunctionOption() {
  return OptionSpec::text(
             "tf",
             "transfer function: a preset (" + joinedNames(transferFunctionPresetNames()) +
                 "; README 'Transfer-function presets') or a FILE.json list of {\"value\" "
                 "(data units), \"color\", \"opacity\"} points (or that JSON itself), linearly "
                 "interpolated "
                 "(illustrate: instead of the power opacity k_os*v^k_oe over --color; mip, "
                 "lmip, demip: instead of --window's grey ramp)")
      .validatedBy([](const OptionValue& value) {
        if (!textOf(value).empty()) checkTransferFunctionOption(textOf(value));
      });
}

OptionSpec colorOption() {
  return OptionSpec::text("color", "the sample colour without a transfer function (default ivory)")
      .validatedBy([](const OptionValue& value) {
        if (!textOf(value).empty()) parseOpaqueColor(textOf(value), "--color", kSampleColorAlpha);
      });
}

OptionSpec sketchColorOption() {
  return OptionSpec::text("sketch-color", "the colour of sketch lines (default black)")
      .validatedBy([](const OptionValue& value) {
        if (!textOf(value).empty())
          parseOpaqueColor(textOf(value), "--sketch-color", kSketchColorAlpha);
      });
}

IllustrationStyle styleFromOptions(const std::vector<OptionSpec>& declared,
                                   const OptionReader& options) {
  IllustrationStyle style;
  const auto given = [&](const char* name) {
    return declares(declared, name) && options.given(name);
  };
  if (given("effects")) style.effects = parseEffects(options.text("effects"), "--effects");
  if (given("param")) {
    const OptionSpec& spec = *std::find_if(declared.begin(), declared.end(),
                                           [](const OptionSpec& s) { return s.name == "param"; });
    spec.check(options.list("param"));  // the declaring technique's names
    for (const auto& text : options.list("param")) {
      parseParameterList(text, "--param", {}, "", style.parameters);
    }
  }
  if (given("tf") && !options.text("tf").empty()) {
    style.transferFunction = transferFunctionOption(options.text("tf"), options.derived());
  }
  if (given("color") && !options.text("color").empty()) {
    style.color = parseOpaqueColor(options.text("color"), "--color", kSampleColorAlpha);
  }
  if (given("sketch-color") && !options.text("sketch-color").empty()) {
    style.sketchColor =
        parseOpaqueColor(options.text("sketch-color"), "--sketch-color", kSketchColorAlpha);
  }
  if (given("light") && !options.list("light").empty()) {
    std::vector<Light> lights;
    for (const auto& text : options.list("light")) lights.push_back(parseLight(text, "--light"));
    style.lights = lights;
  }
  return style;
}

Illustration illustrationFromOptions(const std::vector<OptionSpec>& declared,
                                     const OptionReader& options,
                                     const IllustrationStyle& defaults) {
  const bool styled =
      declares(declared, "style") && options.given("style") && !options.text("style").empty();
  const IllustrationStyle base = styled ? loadStyle(options.text("style")) : defaults;
  Illustration illustration = resolveIllustration(base, styleFromOptions(declared, options),
                                                  styled ? options.text("style") : "");
  illustration.powerOpacityFrom = float(options.derived().iso);
  illustration.powerOpacityTo = float(defaultClassificationTop(options.derived()));
  return illustration;
}

}  // namespace vsil
