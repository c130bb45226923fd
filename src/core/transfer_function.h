#pragma once
// Transfer functions: colour and opacity by sample value. The file format (`--tf FILE`, and
// the "transfer_function" of an illustration style) is a JSON list of control points in the
// data's own units,
//
//   [{"value": 0, "color": "#000000", "opacity": 0},
//    {"value": 40, "color": "#c08040", "opacity": 0.02},
//    {"value": 255, "color": "#fffff0", "opacity": 0.8}]
//
// values non-decreasing (two equal values make a step), colours as everywhere (core/color.h;
// the alpha of #rrggbbaa is ignored: opacity says it), opacity in [0, 1] per voxel of
// distance along the view (the opacity correction of slicing/compositing.h scales it to the
// slice distance). Between points colour and opacity are interpolated linearly; beyond the
// first and last point they stay constant. Shared by every technique that classifies samples
// (illustrate; mip and semantic next): the parser here (CPU, fuzzed), the 1D texture in
// slicing/transfer_function_texture.h.
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json_fwd.hpp>

#include "core/options.h"
#include "core/volume.h"

namespace vsil {

struct TransferPoint {
  double value = 0;
  glm::dvec3 color{1.0};  // straight RGB in [0, 1]
  double opacity = 0;
};

struct TransferFunction {
  std::vector<TransferPoint> points;  // at least one, values non-decreasing
  std::string source;                 // the file, or "<style>: transfer_function"

  // Straight RGB and opacity at `value`: linear between the points, constant beyond them; at a
  // step (equal values) the later point wins.
  glm::dvec4 at(double value) const;
  // `size` entries (>= 2) spanning `range`: entry i is at(range.min + i·(max − min)/(size − 1)).
  std::vector<glm::vec4> table(ValueRange range, int size) const;
  nlohmann::json toJson() const;
};

// Control points at most (a table of 4096 entries resolves far fewer).
inline constexpr std::size_t kMaxTransferPoints = 4096;

// `json` must be the list above. InputError "<source>: point N: ..." (N from 1) naming what is
// wrong: not a list, empty, too many points, a point that is not an object, a missing or
// unknown key, a value that is not a finite number, a bad colour, an opacity outside [0, 1],
// a value below the previous point's.
TransferFunction parseTransferFunction(const nlohmann::json& json, const std::string& source);
// Parses JSON text (InputError "<source>: not valid JSON (...)" first).
TransferFunction parseTransferFunctionText(std::string_view text, const std::string& source);
// Reads and parses a file (at most 1 MiB).
TransferFunction loadTransferFunction(const std::string& path);

// Presets by name (`--tf ct-bone`), in the spirit of 3D Slicer's volume-rendering presets, one
// JSON file each in src/core/tf_presets/ embedded at build time:
//   {"description": "...", "units": "hu" | "window", "points": [the list above]}
// Their values become data values for a volume (its derived defaults, core/options.h):
//  - "hu": Hounsfield units. Data in HU (the value range reaches below −500: a CT with its
//    rescale) take them as they are. Other data (8-bit CT such as engine or bonsai, whose
//    values are no HU) map HU affinely onto the default window, −500 HU (between air and fat,
//    where a CT's threshold between air and body lies) at Otsu's threshold and +3000 HU (dense
//    bone, metal) at the window's top (core/volume.h derivedDefaults), so the preset's materials
//    keep their order and lie above the air and noise.
//  - "window": 0 at Otsu's threshold, 1 at the top of the default window (mr-default, ramp).
inline constexpr double kHounsfieldAtOtsu = -500.0;
inline constexpr double kHounsfieldAtWindowTop = 3000.0;
// Whether a volume's values read as Hounsfield units.
bool inHounsfieldUnits(const DerivedDefaults& volume);
// Where the default classifications without a transfer function (illustrate's power opacity,
// semantic's default rule base), which start at Otsu's threshold, reach their top: the default
// MIP window's top (the 99.5th percentile above the threshold), so that a few bright voxels (the
// hydrogen atom's nucleus) do not leave the rest near transparent; never above the range's top.
// Data in Hounsfield units keep the range's top: a CT's soft tissue lies far below its bone, and
// a top in bone made it an opaque barrel (round 21; CTs take --tf ct-bone, as info suggests).
double defaultClassificationTop(const DerivedDefaults& volume);
// The values such a classification spans in `range`: from `from` (clamped to the range) to
// `to`, or to the range's top where `to` is not between them.
ValueRange classificationDomain(float from, float to, ValueRange range);
std::vector<std::string> transferFunctionPresetNames();  // sorted
// Whether `text` names a file (ends in .json or holds a '/') rather than a preset.
bool isTransferFunctionFile(std::string_view text);
// Whether a --tf value names a preset: neither inline JSON nor a file.
bool isTransferFunctionPreset(std::string_view text);
// A preset's data values for `volume`; InputError "--tf: unknown preset 'x' (presets: ...; or a
// .json file)" for a name that is none.
TransferFunction transferFunctionPreset(const std::string& name, const DerivedDefaults& volume);
// What --tf NAME|FILE gives for `volume`: the preset, or the file read.
TransferFunction transferFunctionOption(const std::string& nameOrFile,
                                        const DerivedDefaults& volume);
// Checks --tf before any volume is read: the file parses, or the preset exists.
void checkTransferFunctionOption(const std::string& nameOrFile);
// The preset `vsil info` suggests for a volume: ct-bone for data in HU, ramp otherwise (an MR
// cannot be told from its values: mr-default is the user's choice).
std::string suggestedTransferFunction(const DerivedDefaults& volume);

}  // namespace vsil
