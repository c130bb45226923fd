#pragma once
// Parsing of compound flag values ("512x384"). Errors name the flag.
#include <string>

#include <glm/glm.hpp>

namespace CLI {
class App;
class Option;
class ParseError;
}  // namespace CLI

namespace vsil::cli {

// Refuses an empty value for `option` (--crop '', a shell variable left unset): InputError
// "<flag>: is empty: give a value, or leave the flag out", never the flag read as left out.
CLI::Option* nonEmpty(CLI::Option* option);

// CLI11 reads a whole number beyond long long as the largest one (99999999999999999999 became
// 9223372036854775807, and messages quoted that): every whole-number option of `app` and its
// subcommands refuses such a value as written, InputError "<flag> <text>: is beyond every whole
// number the flag takes". Call once the options are added.
void refuseWholeNumbersBeyondRange(CLI::App& app);

// "WxH" with positive integers.
glm::ivec2 parseSize(const std::string& flag, const std::string& text);
// "A,B" with finite numbers: core/number_pair.h parseNumberPair.

// CLI11's message for a parse error, in the words of vsil's own: "--zoom: 'abc' is not a value
// it takes" for "Could not convert: --zoom = abc", "--zoom: given more than once" for "--zoom: At
// Most 1 required but received 2"; other messages as CLI11 words them.
std::string parseErrorText(const CLI::ParseError& error);

}  // namespace vsil::cli
