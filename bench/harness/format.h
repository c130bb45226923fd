#pragma once
// How the tables print numbers: frame rates, ratios, volume sizes.
#include <string>

#include <glm/glm.hpp>

namespace vsil::bench {

// "143", "42.8", "9.85"; "–" for nothing measured (≤ 0 or NaN).
std::string formatFps(double fps);
// "1.23"; "–" when not positive or not finite.
std::string formatRatio(double ratio);
// "256³", "256²·128", "128·96·40".
std::string dimsLabel(glm::ivec3 dims);

}  // namespace vsil::bench
