#pragma once
// Parsing of compound flag values ("512x384"). Errors name the flag.
#include <string>

#include <glm/glm.hpp>

namespace CLI {
class Option;
class ParseError;
}  // namespace CLI

namespace vsil::cli {

// Refuses an empty value for `option` (--crop '', a shell variable left unset): InputError
// "<flag>: is empty: give a value, or leave the flag out", never the flag read as left out.
CLI::Option* nonEmpty(CLI::Option* option);

// "WxH" with positive integers.
glm::ivec2 parseSize(const std::string& flag, const std::string& text);
// "A,B" with finite numbers: core/number_pair.h parseNumberPair.

// CLI11's message for a parse error, in the words of vsil's own: "--zoom: 'abc' is not a value
// it takes" for "Could not convert: --zoom = abc", "--zoom: given more than once" for "--zoom: At
// Most 1 required but received 2"; other messages as CLI11 words them.
std::string parseErrorText(const CLI::ParseError& error);

}  // namespace vsil::cli
