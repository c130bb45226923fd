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

}  // namespace vsil
