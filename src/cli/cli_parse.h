#pragma once
// Parsing of compound flag values ("512x384"). Errors name the flag.
#include <string>

#include <glm/glm.hpp>

namespace CLI {
class Option;
}

namespace vsil::cli {

// Refuses an empty value for `option` (--crop '', a shell variable left unset): InputError
// "<flag>: is empty: give a value, or leave the flag out", never the flag read as left out.
CLI::Option* nonEmpty(CLI::Option* option);

// "WxH" with positive integers.
glm::ivec2 parseSize(const std::string& flag, const std::string& text);
// "A,B" with finite numbers: core/number_pair.h parseNumberPair.

}  // namespace vsil::cli
