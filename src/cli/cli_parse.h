#pragma once
// Parsing of compound flag values ("512x384", "30,20"). Errors name the flag.
#include <string>

#include <glm/glm.hpp>

namespace vsil::cli {

// "WxH" with positive integers.
glm::ivec2 parseSize(const std::string& flag, const std::string& text);
// "A,B" with finite numbers.
glm::dvec2 parsePair(const std::string& flag, const std::string& text);

}  // namespace vsil::cli
