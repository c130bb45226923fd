#pragma once
// "A,B": two finite numbers, the form of --view, --window, --sphere-rotate. Errors name the flag.
#include <string>

#include <glm/glm.hpp>

namespace vsil {

glm::dvec2 parseNumberPair(const std::string& flag, const std::string& text);

}  // namespace vsil
