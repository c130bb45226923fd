#pragma once
// Ebert–Rheingans volume illustration (IEEE Vis 2000), the CPU side: the effects by name, the
// parameters by the paper's names with their defaults and ranges, lights, and styles (a JSON
// file or an embedded preset holding any combination of effects, parameters, transfer
// function, colours and lights). The GL side is slicing/techniques/illustrate/ (the formulas
// in slicing/shaders/illustration.glsl); the CPU reference tests/reference/illustrate_reference.
//
// Everything here is plain data and parsing (no GL), so the style and transfer-function readers
// are fuzz targets (tests/fuzz/fuzz_style.cpp, fuzz_tf.cpp).
#include <filesystem>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json_fwd.hpp>

#include "core/color.h"
#include "core/transfer_function.h"

namespace vsil {

// The paper's effects, in the order the slice shader applies them to a sample.
enum class Effect { Boundary, Silhouette, Fading, Sketch, Distance, Halo, Tone };
inline constexpr int kEffectCount = 7;

const char* effectName(Effect effect);

class EffectSet {
 public:
  bool has(Effect effect) const { return (bits_ >> int(effect)) & 1u; }
  void add(Effect effect) { bits_ |= 1u << int(effect); }
  bool empty() const { return bits_ == 0; }
  std::vector<Effect> list() const;        // in Effect order
  std::vector<std::string> names() const;  // in Effect order
  bool operator==(const EffectSet&) const = default;

 private:
  unsigned bits_ = 0;
};

// "boundary,tone" (comma-separated, spaces around names allowed, "" or "none" for no effect);
// InputError "<where>: unknown effect 'x' (known: boundary, ...)".
EffectSet parseEffects(std::string_view text, const std::string& where);

// Why a sample colour and a sketch colour take no alpha (core/color.h parseOpaqueColor), for the
// flags and the style files alike.
inline constexpr const char* kSampleColorAlpha =
    "a sample's opacity comes from the transfer function";
inline constexpr const char* kSketchColorAlpha = "a sketch line's opacity comes from k_ls and k_le";

// One parameter: the paper's name (k_gc ...) or ours where the paper has none.
struct ParameterSpec {
  std::string name;
  double defaultValue = 0;
  double min = 0;  // inclusive, unless minExclusive
  bool minExclusive = false;
  double max = 1e9;              // inclusive
  std::optional<Effect> effect;  // the effect it shapes; none: transfer function and lighting
  std::string meaning;           // one line, for help and the README
};

// Every parameter, grouped by effect. Defaults are the values of the paper's figures where it
// gives them (Figure 4 for boundary and silhouette, 6 for distance blending and halos, 7 and 8
// for tone shading); ours where it does not, with the reason in illustration.cpp.
const std::vector<ParameterSpec>& illustrationParameters();
const ParameterSpec* findParameter(std::string_view name);

// Parameter values by name.
using ParameterValues = std::map<std::string, double, std::less<>>;

// Every parameter at its default.
ParameterValues defaultParameters();

// Parses "k_gc=0.8,k_gs=5" into `values` (later names win). `allowed`: the names this caller
// accepts (empty: every parameter); `owner` names the caller in the message for a name it does
// not accept. InputError "<where>: ..." for an unknown name, a missing '=', a value that is not
// a finite number, or one outside the parameter's range.
void parseParameterList(std::string_view text, const std::string& where,
                        const std::vector<std::string>& allowed, const std::string& owner,
                        ParameterValues& values);
// Checks one value against its parameter's range; InputError "<where>: k_gc: must be ...".
void checkParameter(const ParameterSpec& spec, double value, const std::string& where);

// A directional light, its direction given relative to the view: azimuth about the view's up
// axis (0: from the viewer, 90: from the right), elevation towards the view's up (90: straight
// above). The paper's default: one light above the volume and slightly toward the viewer.
struct Light {
  double azimuthDeg = 0;
  double elevationDeg = 60;
  bool operator==(const Light&) const = default;
  // Unit vector towards the light in eye space (x right, y up, z towards the viewer).
  glm::dvec3 directionEye() const;
};
inline constexpr std::size_t kMaxLights = 8;

// "AZ,EL" in degrees, finite, elevation in [-90, 90]; InputError "<where>: ...".
Light parseLight(std::string_view text, const std::string& where);

// A style as given (a file, a preset, or options): only what it sets.
struct IllustrationStyle {
  std::optional<EffectSet> effects;
  ParameterValues parameters;
  std::optional<TransferFunction> transferFunction;
  std::optional<Rgba> color;        // the sample colour without a transfer function
  std::optional<Rgba> sketchColor;  // sketch lines
  std::optional<Rgba> background;   // c_b of distance blending, and what the frame is composed over
  std::optional<std::vector<Light>> lights;
  std::string description;
};

// A style file:
//   {"description": "...", "effects": ["boundary", "silhouette"] (or "boundary,silhouette"),
//    "parameters": {"k_gc": 0.8, ...}, "transfer_function": [points] or "file.json",
//    "color": "ivory", "sketch_color": "black", "background": "#000026",
//    "lights": ["0,60", [30, 45]]}
// Every key optional, unknown keys refused. A transfer function given as a file name is read
// relative to `baseDir`. InputError "<source>: <key>: ..." for anything malformed.
IllustrationStyle parseStyle(const nlohmann::json& json, const std::string& source,
                             const std::filesystem::path& baseDir);
IllustrationStyle parseStyleText(std::string_view text, const std::string& source,
                                 const std::filesystem::path& baseDir);

// The presets embedded at build time (src/core/styles/*.json), by name
// ("fig4-boundary-silhouette").
std::vector<std::string> stylePresetNames();
// `nameOrFile`: a preset name, or a path to a .json style file. InputError for an unknown
// preset ("--style: unknown preset 'x' (presets: ...; or a .json file)") or a bad file.
IllustrationStyle loadStyle(const std::string& nameOrFile);
// Whether `text` names a style file (ends in .json) rather than a preset.
bool isStyleFile(std::string_view text);

// What a frame uses: a style resolved against the defaults.
struct Illustration {
  EffectSet effects;
  ParameterValues parameters;                        // every parameter
  std::optional<TransferFunction> transferFunction;  // none: o_v = k_os·v^k_oe over `color`
  Rgba color{255, 255, 240, 255};                    // ivory
  Rgba sketchColor{0, 0, 0, 255};
  std::optional<Rgba> background;  // the style's, if it sets one (--background wins)
  std::vector<Light> lights{Light{}};
  std::string style;  // the preset or file it started from ("" for none)
  // Without a transfer function, where the power opacity starts: v = (value − this) / (max −
  // this) clamped to [0, 1], so values at or below it are transparent. Otsu's threshold of the
  // volume (DerivedDefaults::iso, the default --iso), so that CT air and noise do not become a
  // fog box (illustration_options.cpp illustrationFromOptions); the paper leaves the transfer
  // function to the user.
  float powerOpacityFrom = 0.0f;
  // Where v reaches 1 (core/transfer_function.h defaultClassificationTop: the top of the MIP
  // family's default window, the range's for data in Hounsfield units); infinity: the range's.
  float powerOpacityTo = std::numeric_limits<float>::infinity();

  double operator[](std::string_view name) const;
  // For --meta-out: effects, every parameter, colours, lights, the transfer function.
  nlohmann::json toJson() const;
};

// Tone shading's peak: the largest channel that the paper's sum
// I = k_ta·I_G + Σ_lights (I_t + k_td·I_o) (shaders/illustration.glsl toneShade) reaches for a
// white object over every normal, with these parameters and lights. The shaders divide the sum
// by max(1, peak): then it stays within [0, 1] for every object colour within [0, 1] (the sum
// grows with each channel of the colour), and one factor for all colours keeps the paper's
// proportions of lit colour, warm, cool and directed light. Exact for any number of lights:
// the sum is C + max over subsets S of the lights of w_S·n (S the lights n faces), so its
// maximum over unit n is C + max_S |w_S|.
double toneShadingPeak(const Illustration& illustration);

// `base` (a loaded style, or empty), then each field `overrides` sets, over the defaults.
Illustration resolveIllustration(const IllustrationStyle& base, const IllustrationStyle& overrides,
                                 std::string styleName);

}  // namespace vsil
