#pragma once
// How the tables print numbers (frame rates, ratios, volume sizes) and their cases' checks.
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace vsil::bench {

// "143", "42.8", "9.85"; "–" for nothing measured (≤ 0 or NaN).
std::string formatFps(double fps);
// "1.23"; "–" when not positive or not finite.
std::string formatRatio(double ratio);
// "256³", "256²·128", "128·96·40".
std::string dimsLabel(glm::ivec3 dims);
// A case's failed checks with "; " between them ("" when all passed).
std::string joinedProblems(const std::vector<std::string>& problems);
// "ok", or "FAILED: " and the failed checks: the `check` cell and JSON field.
std::string checkText(const std::vector<std::string>& problems);

}  // namespace vsil::bench
