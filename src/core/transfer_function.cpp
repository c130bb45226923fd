#include "core/transfer_function.h"

#include <algorithm>
#include <cmath>

#include <nlohmann/json.hpp>

#include "core/color.h"
#include "core/error.h"
#include "core/json_input.h"

namespace vsil {

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
  const double t = (value - low.value) / (high.value - low.value);  // high > low here
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
    const Rgba color = parseColor(jsonString(item["color"], where + ": color"), where + ": color");
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

}  // namespace vsil
