#pragma once
// Parsing of compound flag values ("512x384"). Errors name the flag.
#include <string>

#include <glm/glm.hpp>

namespace vsil::cli {

// "WxH" with positive integers.
glm::ivec2 parseSize(const std::string& flag, const std::string& text);
// "A,B" with finite numbers: core/number_pair.h parseNumberPair.

}  // namespace vsil::cli
