#pragma once
// The technique flags of `vsil render` (and every command that renders): --technique and every
// option every technique declares (slicing/technique_table.h), each flag once, with its help,
// default and range from the table. Values are parsed and range-checked as they are read; after
// parsing, RenderJob::checkRequest reports options the chosen technique does not have.
#include <CLI/CLI.hpp>

#include "core/options.h"

namespace vsil::cli {

// `technique` and `values` must outlive the parse.
void addTechniqueOptions(CLI::App& command, std::string& technique, OptionValues& values);

}  // namespace vsil::cli
