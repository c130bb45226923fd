#include "core/illustration.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <numbers>
#include <sstream>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/json_input.h"
#include "core/options.h"

namespace vsil {

// The presets embedded at build time (src/CMakeLists.txt), keyed "<name>.json".
std::string_view embeddedStyleSource(std::string_view path);
std::vector<std::string_view> embeddedStylePaths();

namespace {

constexpr const char* kEffectNames[kEffectCount] = {"boundary", "silhouette", "fading", "sketch",
                                                    "distance", "halo",       "tone"};

std::string_view trimmed(std::string_view text) {
  const auto isSpace = [](char c) { return c == ' ' || c == '\t'; };
  while (!text.empty() && isSpace(text.front())) text.remove_prefix(1);
  while (!text.empty() && isSpace(text.back())) text.remove_suffix(1);
  return text;
}

std::vector<std::string_view> splitCommas(std::string_view text) {
  std::vector<std::string_view> parts;
  for (;;) {
    const auto comma = text.find(',');
    parts.push_back(trimmed(text.substr(0, comma)));
    if (comma == std::string_view::npos) return parts;
    text.remove_prefix(comma + 1);
  }
}

// Quoted for messages, shortened: the user's text may be anything.
std::string quotedText(std::string_view text) {
  constexpr std::size_t kMax = 40;
  std::string shown(text.substr(0, kMax));
  for (char& c : shown) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
  }
  return "'" + shown + (text.size() > kMax ? "...'" : "'");
}

// A whole text as a finite double, or nothing.
std::optional<double> parseNumber(std::string_view text) {
  double value = 0;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (ec != std::errc() || ptr != end || text.empty()) return std::nullopt;
  return value;
}

ParameterSpec parameter(std::string name, double defaultValue, std::optional<Effect> effect,
                        std::string meaning) {
  ParameterSpec spec;
  spec.name = std::move(name);
  spec.defaultValue = defaultValue;
  spec.effect = effect;
  spec.meaning = std::move(meaning);
  spec.max = 1e6;
  return spec;
}
// Exponents must be positive: pow(0, 0) has no value in GLSL.
ParameterSpec exponent(std::string name, double defaultValue, std::optional<Effect> effect,
                       std::string meaning) {
  ParameterSpec spec = parameter(std::move(name), defaultValue, effect, std::move(meaning));
  spec.minExclusive = true;
  spec.max = 1000;
  return spec;
}
ParameterSpec fraction(std::string name, double defaultValue, std::optional<Effect> effect,
                       std::string meaning) {
  ParameterSpec spec = parameter(std::move(name), defaultValue, effect, std::move(meaning));
  spec.max = 1;
  return spec;
}

std::vector<ParameterSpec> makeParameters() {
  using E = Effect;
  std::vector<ParameterSpec> specs = {
      // Transfer function and lighting. The paper gives no k_os, k_oe: 1 and 2 keep the
      // low-valued noise of CT air nearly transparent (o_v = v²) while dense material saturates.
      parameter("k_os", 1.0, {},
                "opacity scale: o_v = k_os·v^k_oe, v the value normalized to [0, 1]"),
      exponent("k_oe", 2.0, {}, "opacity exponent (< 1 softens, > 1 raises contrast)"),
      // The plain lit composite (the paper's I_G, its gaseous illumination): ambient plus
      // diffuse from the lights, ours.
      parameter("k_a", 0.3, {}, "ambient share of the lit colour"),
      parameter("k_d", 0.7, {}, "diffuse share of the lit colour, per light"),
      // Boundary enhancement, ours: o_v·|∇f| (Levoy's, the paper's "k_gc = 0: only areas with
      // large gradients"). Every sample's opacity here is per voxel and the plain composite is
      // near opaque after a few voxels of dense material, so any k_gc above a few hundredths
      // leaves homogeneous insides opaque and changes nothing visible (Figure 4's 0.8, 5, 1:
      // 2/255 on the engine); with k_gc = 0 the insides fade and the surfaces between materials
      // remain, as in Figure 3. The presets name the paper's values (fig3, fig4).
      parameter("k_gc", 0.0, E::Boundary, "boundary: share of the original opacity"),
      parameter("k_gs", 1.0, E::Boundary, "boundary: scale of the gradient term"),
      exponent("k_ge", 1.0, E::Boundary, "boundary: exponent of the gradient magnitude"),
      // Figure 4.
      parameter("k_sc", 0.9, E::Silhouette, "silhouette: scale of non-silhouette regions"),
      parameter("k_ss", 50.0, E::Silhouette, "silhouette: amount of enhancement"),
      exponent("k_se", 0.25, E::Silhouette, "silhouette: sharpness"),
      // Oriented fading (Figure 9), ours: with f = |∇f_n·V|^k_fe (1 facing the viewer),
      // saturation ×(1 − k_fs·f), value ×(1 − k_fv·(1 − f)), opacity ×(1 − k_fo·f).
      fraction("k_fs", 0.8, E::Fading, "fading: desaturation of regions facing the viewer"),
      fraction("k_fv", 0.6, E::Fading, "fading: darkening of regions turned away"),
      fraction("k_fo", 0.0, E::Fading, "fading: transparency of regions facing the viewer"),
      exponent("k_fe", 1.0, E::Fading, "fading: exponent of |∇f_n·V|"),
      // Sketch lines (Figure 5), ours: opacity ×min(1, k_ls·|∇f|²·(1 − |∇f_n·V|)^k_le), colour
      // the sketch colour. k_ls = 16 saturates lines where |∇f| is 0.25 (a CT's surfaces) and
      // the surface is edge-on, and keeps a noisy inside (|∇f| about 0.05) near transparent;
      // k_le = 4 keeps the lines thin (k_le = 2 blackened the outer third of a ball's disc).
      parameter("k_ls", 16.0, E::Sketch, "sketch: line opacity scale"),
      exponent("k_le", 4.0, E::Sketch, "sketch: line sharpness"),
      // Figure 6 (its "kse = 0.5" is k_de).
      fraction("k_ds", 1.0, E::Distance, "distance: size of the blend towards c_b"),
      exponent("k_de", 0.5, E::Distance, "distance: rate of the blend with depth"),
      exponent("k_hpe", 1.0, E::Halo,
               "halo: how directly a neighbour's normal must point at the sample"),
      exponent("k_hse", 2.0, E::Halo, "halo: how tightly halos stay in the plane across the view"),
      // Ours: the paper's two scalars and the neighbourhood's radius (4 voxels: halos visible
      // at 256², still 2.9× the plain composite's frame time, README's illustrate table).
      parameter("k_hd", 2.0, E::Halo, "halo: darkening, colour ×max(0, 1 − k_hd·h)"),
      parameter("k_ho", 1.0, E::Halo, "halo: added opacity, + k_ho·h"),
      parameter("k_hr", 4.0, E::Halo, "halo: radius of the neighbourhood in voxels"),
      // Figures 7 and 8.
      parameter("k_ta", 1.0, E::Tone, "tone: amount of the lit colour I_G"),
      parameter("k_td", 0.6, E::Tone, "tone: amount of directed illumination"),
      fraction("k_ty", 0.3, E::Tone, "tone: warm colour (k_ty, k_ty, 0)"),
      fraction("k_tb", 0.3, E::Tone, "tone: cool colour (0, 0, k_tb)"),
  };
  for (auto& spec : specs) {
    if (spec.name == "k_hr") {
      spec.min = 0.5;
      spec.max = 32;
    }
  }
  return specs;
}

}  // namespace

const char* effectName(Effect effect) {
  return kEffectNames[int(effect)];
}

std::vector<Effect> EffectSet::list() const {
  std::vector<Effect> effects;
  for (int i = 0; i < kEffectCount; ++i) {
    if (has(Effect(i))) effects.push_back(Effect(i));
  }
  return effects;
}

std::vector<std::string> EffectSet::names() const {
  std::vector<std::string> names;
  for (Effect e : list()) names.emplace_back(effectName(e));
  return names;
}

namespace {

// Adds `effect`, refusing one `effects` holds already (--effects halo,halo).
void addEffectOnce(EffectSet& effects, Effect effect, const std::string& where) {
  if (effects.has(effect)) {
    throwInputError(where, "effect " + quotedText(effectName(effect)) + " is named twice");
  }
  effects.add(effect);
}

}  // namespace

constexpr const char* kNoneStandsAlone = "'none' (no effect) stands alone, not beside others";

EffectSet parseEffects(std::string_view text, const std::string& where) {
  EffectSet effects;
  if (trimmed(text).empty() || trimmed(text) == "none") return effects;
  for (std::string_view name : splitCommas(text)) {
    if (name == "none") throwInputError(where, kNoneStandsAlone);
    const auto* found = std::find(std::begin(kEffectNames), std::end(kEffectNames), name);
    if (found == std::end(kEffectNames)) {
      throwInputError(where, "unknown effect " + quotedText(name) + " (known: " +
                                 joined({std::begin(kEffectNames), std::end(kEffectNames)}) + ")");
    }
    addEffectOnce(effects, Effect(found - std::begin(kEffectNames)), where);
  }
  return effects;
}

const std::vector<ParameterSpec>& illustrationParameters() {
  static const std::vector<ParameterSpec> specs = makeParameters();
  return specs;
}

const ParameterSpec* findParameter(std::string_view name) {
  for (const auto& spec : illustrationParameters()) {
    if (spec.name == name) return &spec;
  }
  return nullptr;
}

ParameterValues defaultParameters() {
  ParameterValues values;
  for (const auto& spec : illustrationParameters()) values.emplace(spec.name, spec.defaultValue);
  return values;
}

void checkParameter(const ParameterSpec& spec, double value, const std::string& where) {
  const std::string name = where + ": " + spec.name;
  if (!std::isfinite(value)) throwInputError(name, "must be a finite number");
  const bool belowMin = spec.minExclusive ? !(value > spec.min) : !(value >= spec.min);
  if (belowMin || !(value <= spec.max)) {
    throwInputError(name, std::string("must be in ") + (spec.minExclusive ? "(" : "[") +
                              formatNumber(spec.min) + ", " + formatNumber(spec.max) + "] (got " +
                              formatNumber(value) + ")");
  }
}

void parseParameterList(std::string_view text, const std::string& where,
                        const std::vector<std::string>& allowed, const std::string& owner,
                        ParameterValues& values) {
  for (std::string_view item : splitCommas(text)) {
    const auto equals = item.find('=');
    if (equals == std::string_view::npos) {
      throwInputError(where, quotedText(item) + " is not NAME=VALUE");
    }
    const std::string_view name = trimmed(item.substr(0, equals));
    const std::string_view valueText = trimmed(item.substr(equals + 1));
    const ParameterSpec* spec = findParameter(name);
    const bool accepted = spec && (allowed.empty() || std::find(allowed.begin(), allowed.end(),
                                                                name) != allowed.end());
    if (!accepted) {
      std::vector<std::string> known = allowed;
      if (known.empty()) {
        for (const auto& s : illustrationParameters()) known.push_back(s.name);
      }
      throwInputError(where, quotedText(name) + " is not a parameter" +
                                 (owner.empty() ? "" : " of " + owner) +
                                 " (known: " + joined(known) + ")");
    }
    const auto value = parseNumber(valueText);
    if (!value) {
      double ignored = 0;
      const bool outOfRange =
          std::from_chars(valueText.data(), valueText.data() + valueText.size(), ignored).ec ==
          std::errc::result_out_of_range;
      throwInputError(
          where + ": " + spec->name,
          quotedText(valueText) + (outOfRange ? " is out of range" : " is not a number"));
    }
    checkParameter(*spec, *value, where);
    values[spec->name] = *value;
  }
}

glm::dvec3 Light::directionEye() const {
  // Whole turns first: 1.7e308 degrees times pi/180 overflowed to inf (a NaN direction).
  const double az = std::fmod(azimuthDeg, 360.0) * std::numbers::pi / 180.0;
  const double el = std::fmod(elevationDeg, 360.0) * std::numbers::pi / 180.0;
  return {std::sin(az) * std::cos(el), std::sin(el), std::cos(az) * std::cos(el)};
}

Light parseLight(std::string_view text, const std::string& where) {
  const auto parts = splitCommas(text);
  if (parts.size() != 2) throwInputError(where, quotedText(text) + " is not AZ,EL (degrees)");
  const auto az = parseNumber(parts[0]), el = parseNumber(parts[1]);
  if (!az || !el) throwInputError(where, quotedText(text) + " is not AZ,EL (degrees)");
  if (!std::isfinite(*az) || !std::isfinite(*el)) {
    throwInputError(where, "angles must be finite (got " + quotedText(text) + ")");
  }
  if (*el < -90.0 || *el > 90.0) {
    throwInputError(where, "elevation must be in [-90, 90] (got " + formatNumber(*el) + ")");
  }
  return {*az, *el};
}

namespace {

// `opaqueWhy`: why the colour takes no alpha (parseOpaqueColor), or null where it may have one.
Rgba styleColor(const nlohmann::json& value, const std::string& where,
                const char* opaqueWhy = nullptr) {
  const std::string text = jsonString(value, where);
  return opaqueWhy ? parseOpaqueColor(text, where, opaqueWhy) : parseColor(text, where);
}

EffectSet styleEffects(const nlohmann::json& value, const std::string& where) {
  if (value.is_string()) return parseEffects(value.get_ref<const std::string&>(), where);
  if (!value.is_array()) {
    throwInputError(where, "must be a list of effect names (got " + jsonSnippet(value) + ")");
  }
  EffectSet effects;
  for (std::size_t i = 0; i < value.size(); ++i) {
    const std::string at = where + " " + std::to_string(i + 1);
    if (value.size() > 1 && trimmed(jsonString(value[i], at)) == "none") {
      throwInputError(at, kNoneStandsAlone);
    }
    for (Effect e : parseEffects(jsonString(value[i], at), at).list())
      addEffectOnce(effects, e, at);
  }
  return effects;
}

std::vector<Light> styleLights(const nlohmann::json& value, const std::string& where) {
  if (!value.is_array()) {
    throwInputError(
        where, "must be a list of lights \"AZ,EL\" or [AZ, EL] (got " + jsonSnippet(value) + ")");
  }
  if (value.empty() || value.size() > kMaxLights) {
    throwInputError(where, "must hold 1 to " + std::to_string(kMaxLights) + " lights (got " +
                               std::to_string(value.size()) + ")");
  }
  std::vector<Light> lights;
  for (std::size_t i = 0; i < value.size(); ++i) {
    const std::string at = where + " " + std::to_string(i + 1);
    const nlohmann::json& item = value[i];
    if (item.is_array()) {
      if (item.size() != 2) throwInputError(at, "must be [AZ, EL] (got " + jsonSnippet(item) + ")");
      const double az = jsonNumber(item[0], at), el = jsonNumber(item[1], at);
      lights.push_back(parseLight(formatNumber(az) + "," + formatNumber(el), at));
    } else {
      lights.push_back(parseLight(jsonString(item, at), at));
    }
  }
  return lights;
}

}  // namespace

IllustrationStyle parseStyle(const nlohmann::json& json, const std::string& source,
                             const std::filesystem::path& baseDir) {
  if (!json.is_object()) {
    throwInputError(source,
                    "must be a JSON object of style settings (got " + jsonSnippet(json) + ")");
  }
  checkJsonKeys(json,
                {"description", "effects", "parameters", "transfer_function", "color",
                 "sketch_color", "background", "lights"},
                source);
  IllustrationStyle style;
  const auto where = [&](const char* key) { return source + ": " + key; };
  if (json.contains("description")) {
    style.description = jsonString(json["description"], where("description"));
  }
  if (json.contains("effects")) style.effects = styleEffects(json["effects"], where("effects"));
  if (json.contains("parameters")) {
    const nlohmann::json& parameters = json["parameters"];
    if (!parameters.is_object()) {
      throwInputError(where("parameters"), "must be an object {\"k_gc\": 0.8, ...} (got " +
                                               jsonSnippet(parameters) + ")");
    }
    for (const auto& item : parameters.items()) {
      const ParameterSpec* spec = findParameter(item.key());
      if (!spec) {
        std::vector<std::string> known;
        for (const auto& s : illustrationParameters()) known.push_back(s.name);
        throwInputError(
            where("parameters"),
            quotedText(item.key()) + " is not a parameter (known: " + joined(known) + ")");
      }
      const double value = jsonNumber(item.value(), where("parameters") + ": " + spec->name);
      checkParameter(*spec, value, where("parameters"));
      style.parameters[spec->name] = value;
    }
  }
  if (json.contains("transfer_function")) {
    const nlohmann::json& tf = json["transfer_function"];
    if (tf.is_string()) {
      const std::string& text = tf.get_ref<const std::string&>();
      if (text.empty()) {
        throwInputError(where("transfer_function"),
                        "is empty: name a FILE.json or hold the points");
      }
      std::filesystem::path file = text;
      if (file.is_relative()) file = baseDir / file;
      // A preset scales by the volume's histogram, which a style is read without.
      const auto presets = transferFunctionPresetNames();
      std::error_code error;
      if (std::find(presets.begin(), presets.end(), text) != presets.end() &&
          !std::filesystem::exists(file, error)) {
        throwInputError(where("transfer_function"),
                        quotedText(text) +
                            " is a preset, which goes with --tf; a style names a FILE.json or "
                            "holds the points");
      }
      try {
        style.transferFunction = loadTransferFunction(file.string());
      } catch (const InputError& e) {  // the file's own message, and the style's key it came from
        throwInputError(where("transfer_function"), e.what());
      }
    } else {
      style.transferFunction = parseTransferFunction(tf, where("transfer_function"));
    }
  }
  if (json.contains("color")) {
    style.color = styleColor(json["color"], where("color"), kSampleColorAlpha);
  }
  if (json.contains("sketch_color")) {
    style.sketchColor = styleColor(json["sketch_color"], where("sketch_color"), kSketchColorAlpha);
  }
  if (json.contains("background")) {
    style.background = styleColor(json["background"], where("background"));
  }
  if (json.contains("lights")) style.lights = styleLights(json["lights"], where("lights"));
  return style;
}

IllustrationStyle parseStyleText(std::string_view text, const std::string& source,
                                 const std::filesystem::path& baseDir) {
  return parseStyle(parseJsonText(text, source), source, baseDir);
}

std::vector<std::string> stylePresetNames() {
  std::vector<std::string> names;
  for (std::string_view path : embeddedStylePaths()) {
    if (path.ends_with(".json")) names.emplace_back(path.substr(0, path.size() - 5));
  }
  std::sort(names.begin(), names.end());
  return names;
}

bool isStyleFile(std::string_view text) {
  return text.ends_with(".json") || text.find('/') != std::string_view::npos;
}

IllustrationStyle loadStyle(const std::string& nameOrFile) {
  if (isInlineSource(nameOrFile)) return parseStyleText(nameOrFile, "--style", {});
  if (isStyleFile(nameOrFile)) {
    const std::filesystem::path path(nameOrFile);
    return parseStyle(readJsonFile(nameOrFile), nameOrFile, path.parent_path());
  }
  const auto names = stylePresetNames();
  if (std::find(names.begin(), names.end(), nameOrFile) == names.end()) {
    throwInputError("--style", "unknown preset " + quotedText(nameOrFile) +
                                   " (presets: " + joined(names) + "; or a .json file)");
  }
  // Presets hold their transfer functions inline (there is no folder beside them).
  return parseStyleText(embeddedStyleSource(nameOrFile + ".json"), "preset " + nameOrFile, {});
}

double Illustration::operator[](std::string_view name) const {
  const auto it = parameters.find(name);
  if (it == parameters.end()) {
    throw std::logic_error("Illustration: no parameter '" + std::string(name) + "'");
  }
  return it->second;
}

nlohmann::json Illustration::toJson() const {
  nlohmann::json lightList = nlohmann::json::array();
  for (const auto& light : lights) lightList.push_back({light.azimuthDeg, light.elevationDeg});
  nlohmann::json json = {
      {"style", style},       {"effects", effects.names()},        {"parameters", parameters},
      {"color", color.hex()}, {"sketch_color", sketchColor.hex()}, {"lights", lightList}};
  json["transfer_function"] =
      transferFunction ? transferFunction->toJson() : nlohmann::json("power (k_os, k_oe)");
  if (!transferFunction) {
    json["power_opacity_from"] = powerOpacityFrom;
    if (std::isfinite(powerOpacityTo)) json["power_opacity_to"] = powerOpacityTo;
  }
  if (transferFunction) json["transfer_function_source"] = transferFunction->source;
  return json;
}

double toneShadingPeak(const Illustration& illustration) {
  const Illustration& p = illustration;
  const std::size_t count = p.lights.size();
  glm::dvec3 allLights(0.0);
  for (const Light& light : p.lights) allLights += light.directionEye();
  // Per light, white object, x = n·L: warm channels k_ty·(1 + x)/2, cool k_tb·(1 − x)/2, both
  // + (k_ta·k_d + k_td)·max(x, 0); the ambient k_ta·k_a once.
  const double directed = p["k_ta"] * p["k_d"] + p["k_td"];
  double peak = 0;
  for (const double signedTone : {p["k_ty"] / 2, -p["k_tb"] / 2}) {
    const double constant = p["k_ta"] * p["k_a"] + double(count) * std::abs(signedTone);
    double largest = 0;  // max over S of |w_S|, w_S = signedTone·ΣL + directed·Σ_{i∈S} L_i
    for (std::size_t subset = 0; subset < (std::size_t(1) << count); ++subset) {
      glm::dvec3 w = signedTone * allLights;
      for (std::size_t i = 0; i < count; ++i) {
        if ((subset >> i) & 1u) w += directed * p.lights[i].directionEye();
      }
      largest = std::max(largest, glm::length(w));
    }
    peak = std::max(peak, constant + largest);
  }
  return peak;
}

Illustration resolveIllustration(const IllustrationStyle& base, const IllustrationStyle& overrides,
                                 std::string styleName) {
  Illustration resolved;
  resolved.style = std::move(styleName);
  resolved.parameters = defaultParameters();
  for (const IllustrationStyle* layer : {&base, &overrides}) {
    if (layer->effects) resolved.effects = *layer->effects;
    for (const auto& [name, value] : layer->parameters) resolved.parameters[name] = value;
    if (layer->transferFunction) resolved.transferFunction = layer->transferFunction;
    if (layer->color) resolved.color = *layer->color;
    if (layer->sketchColor) resolved.sketchColor = *layer->sketchColor;
    if (layer->background) resolved.background = layer->background;
    if (layer->lights) resolved.lights = *layer->lights;
  }
  return resolved;
}

}  // namespace vsil
