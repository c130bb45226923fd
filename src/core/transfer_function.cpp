#include "core/transfer_function.h"

#include <algorithm>
#include <cmath>

#include <nlohmann/json.hpp>

#include "core/color.h"
#include "core/error.h"
#include "core/json_input.h"

namespace vsil {

// Generated from src/core/tf_presets/*.json (src/CMakeLists.txt).
std::string_view embeddedTransferFunctionSource(std::string_view path);
std::vector<std::string_view> embeddedTransferFunctionPaths();

glm::dvec4 TransferFunction::at(double value) const {
  if (points.empty()) return glm::dvec4(0.0);
  const auto rgbaOf = [](const TransferPoint& p) { return glm::dvec4(p.color, p.opacity); };
  if (value < points.front().value) return rgbaOf(points.front());
  // The first point above `value`; the one before it is at or below.
  const auto above = std::upper_bound(points.begin(), points.end(), value,
                                      [](double v, const TransferPoint& p) { return v < p.value; });
  if (above == points.end()) return rgbaOf(points.back());
  const TransferPoint& low = *(above - 1);
  const TransferPoint& high = *above;
  // high > low here. Halved first: points near ±1.8e308 lie further apart than a double holds,
  // and the full span would overflow to infinity (t = 0 everywhere between them).
  const double t = (0.5 * value - 0.5 * low.value) / (0.5 * high.value - 0.5 * low.value);
  return rgbaOf(low) * (1.0 - t) + rgbaOf(high) * t;
}

std::vector<glm::vec4> TransferFunction::table(ValueRange range, int size) const {
  std::vector<glm::vec4> entries(std::size_t(std::max(size, 2)));
  const double step = (double(range.max) - double(range.min)) / double(entries.size() - 1);
  for (std::size_t i = 0; i < entries.size(); ++i) {
    entries[i] = glm::vec4(at(double(range.min) + double(i) * step));
  }
  return entries;
}

nlohmann::json TransferFunction::toJson() const {
  nlohmann::json list = nlohmann::json::array();
  for (const auto& p : points) {
    const glm::ivec3 rgb = glm::ivec3(glm::round(p.color * 255.0));
    list.push_back({{"value", p.value},
                    {"color", Rgba{rgb.r, rgb.g, rgb.b, 255}.hex().substr(0, 7)},
                    {"opacity", p.opacity}});
  }
  return list;
}

TransferFunction parseTransferFunction(const nlohmann::json& json, const std::string& source) {
  if (json.is_object() && json.contains("points") && json.contains("units")) {
    throwInputError(source,
                    "holds a preset's {\"units\", \"points\"}, whose values are mapped per "
                    "volume: a file holds the list of points alone, in the data's values (or name "
                    "the preset with --tf)");
  }
  if (!json.is_array()) {
    throwInputError(source,
                    "must be a list of control points {\"value\", \"color\", "
                    "\"opacity\"} (got " +
                        jsonSnippet(json) + ")");
  }
  if (json.empty()) throwInputError(source, "has no control points");
  if (json.size() > kMaxTransferPoints) {
    throwInputError(source, "has " + std::to_string(json.size()) + " control points, more than " +
                                std::to_string(kMaxTransferPoints));
  }
  TransferFunction tf;
  tf.source = source;
  for (std::size_t i = 0; i < json.size(); ++i) {
    const std::string where = source + ": point " + std::to_string(i + 1);
    const nlohmann::json& item = json[i];
    if (!item.is_object()) {
      throwInputError(where, "must be an object {\"value\", \"color\", \"opacity\"} (got " +
                                 jsonSnippet(item) + ")");
    }
    checkJsonKeys(item, {"value", "color", "opacity"}, where);
    for (const char* key : {"value", "color", "opacity"}) {
      if (!item.contains(key)) throwInputError(where, std::string("missing \"") + key + "\"");
    }
    TransferPoint point;
    point.value = jsonNumber(item["value"], where + ": value");
    const Rgba color = parseOpaqueColor(jsonString(item["color"], where + ": color"),
                                        where + ": color", "a point's opacity is its own key");
    point.color = glm::dvec3(color.r, color.g, color.b) / 255.0;
    point.opacity = jsonNumber(item["opacity"], where + ": opacity");
    if (!(point.opacity >= 0.0 && point.opacity <= 1.0)) {
      throwInputError(where + ": opacity",
                      "must be in [0, 1] (got " + jsonSnippet(item["opacity"]) + ")");
    }
    if (!tf.points.empty() && point.value < tf.points.back().value) {
      throwInputError(where, "value " + jsonSnippet(item["value"]) +
                                 " is below the previous point's (values must not decrease)");
    }
    tf.points.push_back(point);
  }
  return tf;
}

TransferFunction parseTransferFunctionText(std::string_view text, const std::string& source) {
  return parseTransferFunction(parseJsonText(text, source), source);
}

TransferFunction loadTransferFunction(const std::string& path) {
  return parseTransferFunction(readJsonFile(path), path);
}

bool inHounsfieldUnits(const DerivedDefaults& volume) {
  return volume.valueMin < -500.0;
}

double defaultClassificationTop(const DerivedDefaults& volume) {
  const double top = volume.valueMin + volume.valueRangeWidth;
  return inHounsfieldUnits(volume) ? top : std::min(volume.windowHigh, top);
}

ValueRange classificationDomain(float from, float to, ValueRange range) {
  const float start = std::clamp(from, range.min, range.max);
  return {start, to > start && to < range.max ? to : range.max};
}

std::vector<std::string> transferFunctionPresetNames() {
  std::vector<std::string> names;
  for (std::string_view path : embeddedTransferFunctionPaths()) {
    if (path.ends_with(".json")) names.emplace_back(path.substr(0, path.size() - 5));
  }
  std::sort(names.begin(), names.end());
  return names;
}

bool isTransferFunctionFile(std::string_view text) {
  return text.ends_with(".json") || text.find('/') != std::string_view::npos;
}

namespace {

void checkPresetName(const std::string& name) {
  const auto names = transferFunctionPresetNames();
  if (std::find(names.begin(), names.end(), name) == names.end()) {
    std::string list;
    for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
    throwInputError("--tf", "unknown preset " + jsonSnippet(nlohmann::json(name)) +
                                " (presets: " + list + "; or a .json file)");
  }
}

}  // namespace

TransferFunction transferFunctionPreset(const std::string& name, const DerivedDefaults& volume) {
  checkPresetName(name);
  const std::string source = "preset " + name;
  const nlohmann::json json = parseJsonText(embeddedTransferFunctionSource(name + ".json"), source);
  TransferFunction tf = parseTransferFunction(json.at("points"), source);
  const std::string units = json.at("units").get<std::string>();
  // value = a + b·(preset value)
  const double low = volume.iso, high = volume.windowHigh;
  double a = 0.0, b = 1.0;
  if (units == "window") {
    a = low, b = high - low;
  } else if (units == "hu") {
    if (!inHounsfieldUnits(volume)) {
      b = (high - low) / (kHounsfieldAtWindowTop - kHounsfieldAtOtsu);
      a = low - kHounsfieldAtOtsu * b;
    }
  } else {
    throw std::logic_error(source + ": units must be \"hu\" or \"window\"");
  }
  for (TransferPoint& point : tf.points) point.value = a + b * point.value;
  return tf;
}

bool isTransferFunctionPreset(std::string_view text) {
  return !isInlineSource(text) && !isTransferFunctionFile(text);
}

TransferFunction transferFunctionOption(const std::string& nameOrFile,
                                        const DerivedDefaults& volume) {
  if (isTransferFunctionPreset(nameOrFile)) return transferFunctionPreset(nameOrFile, volume);
  if (isInlineSource(nameOrFile)) return parseTransferFunctionText(nameOrFile, "--tf");
  return loadTransferFunction(nameOrFile);
}

void checkTransferFunctionOption(const std::string& nameOrFile) {
  if (isTransferFunctionPreset(nameOrFile)) {
    checkPresetName(nameOrFile);
  } else if (isInlineSource(nameOrFile)) {
    parseTransferFunctionText(nameOrFile, "--tf");
  } else {
    loadTransferFunction(nameOrFile);  // InputError naming the file
  }
}

std::string suggestedTransferFunction(const DerivedDefaults& volume) {
  return inHounsfieldUnits(volume) ? "ct-bone" : "ramp";
}

}  // namespace vsil
