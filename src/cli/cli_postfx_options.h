#pragma once
// The postfx flags shared by the commands that write illustrations (vsil render, ...):
//   --width W | --width-near A --width-far B, --line-color, --background, --fill, --fill-color.
// Values are checked as they are parsed; a bad one throws InputError naming its flag.
#include <CLI/CLI.hpp>

#include "postfx/compose.h"

namespace vsil::cli {

// `options` must outlive the parse; it keeps its defaults for flags not given.
void addPostfxOptions(CLI::App& command, vsil::PostfxOptions& options);

// Parses a fill mode name (none, flat, shaded, tone); InputError naming `flagName` otherwise.
vsil::FillMode parseFillMode(const std::string& text, const std::string& flagName);

}  // namespace vsil::cli
