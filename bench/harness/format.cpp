#include "harness/format.h"

#include <cmath>
#include <cstdio>

namespace vsil::bench {

std::string formatFps(double fps) {
  if (!(fps > 0)) return "–";
  char text[32];
  std::snprintf(text, sizeof text, fps >= 100 ? "%.0f" : fps >= 10 ? "%.1f" : "%.2f", fps);
  return text;
}

std::string formatRatio(double ratio) {
  if (!(ratio > 0) || !std::isfinite(ratio)) return "–";
  char text[32];
  std::snprintf(text, sizeof text, "%.2f", ratio);
  return text;
}

std::string dimsLabel(glm::ivec3 dims) {
  if (dims.x == dims.y && dims.y == dims.z) return std::to_string(dims.x) + "³";
  if (dims.x == dims.y) return std::to_string(dims.x) + "²·" + std::to_string(dims.z);
  return std::to_string(dims.x) + "·" + std::to_string(dims.y) + "·" + std::to_string(dims.z);
}

std::string joinedProblems(const std::vector<std::string>& problems) {
  std::string text;
  for (const auto& problem : problems) text += (text.empty() ? "" : "; ") + problem;
  return text;
}

std::string checkText(const std::vector<std::string>& problems) {
  return problems.empty() ? "ok" : "FAILED: " + joinedProblems(problems);
}

}  // namespace vsil::bench
