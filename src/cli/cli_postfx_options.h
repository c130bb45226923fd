#pragma once
// The postfx flags shared by the commands that write illustrations (vsil render, ...):
//   --width W | --width-near A --width-far B, --line-color, --background, --fill, --fill-color.
// Values are checked as they are parsed; a bad one throws InputError naming its flag.
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "postfx/compose.h"

namespace vsil::cli {

// `options` and `lineFlagsGiven` must outlive the parse; `options` keeps its defaults for flags
// not given. The flags that shape lines and filled pixels (all but --background) are appended to
// `lineFlagsGiven` in the order they are declared (each is taken once): they mean something only to
// the techniques that draw lines, and a frame of another technique warns that it ignored them
// (RenderRequest::lineFlagsGiven).
void addPostfxOptions(CLI::App& command, vsil::PostfxOptions& options,
                      std::vector<std::string>& lineFlagsGiven);

// Those line flags, in declaration order: "--width", "--width-near", ..., "--fill-color". The
// serve page's option table marks them (line_flag) and hides them for techniques without lines.
const std::vector<std::string>& lineFlags();

// Parses a fill mode name (none, flat, shaded, tone); InputError naming `flagName` otherwise.
vsil::FillMode parseFillMode(const std::string& text, const std::string& flagName);

}  // namespace vsil::cli
