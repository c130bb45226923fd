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

// Numbers as people write them, in decimal, for every number option of `app` and its
// subcommands (call once the options are added). CLI11 reads C's other notations: 0x10 as 16
// (whole numbers and decimals alike), and 010 as the octal 8 (--frames 010 made 8 frames); a
// whole number beyond long long it reads as the largest one (messages quoted
// 9223372036854775807). Here leading zeros are read as decimal (010 is 10), and a hexadecimal
// number or a whole number beyond range is refused as written: InputError "<flag> <text>: ...".
void readNumbersAsDecimal(CLI::App& app);

// "WxH" with positive integers.
glm::ivec2 parseSize(const std::string& flag, const std::string& text);
// "A,B" with finite numbers: core/number_pair.h parseNumberPair.

// CLI11's message for a parse error, in the words of vsil's own: "--zoom: 'abc' is not a value
// it takes" for "Could not convert: --zoom = abc", "--zoom: given more than once" for "--zoom: At
// Most 1 required but received 2"; other messages as CLI11 words them.
std::string parseErrorText(const CLI::ParseError& error);

}  // namespace vsil::cli
