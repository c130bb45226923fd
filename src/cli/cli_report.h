#pragma once
// Where a command prints its report (the paths it wrote, a summary, a table). Standard output,
// unless one of the command's outputs is standard output (`--json /dev/stdout`): its bytes then
// come there alone, so that `vsil measure-width i.png --json /dev/stdout | jq .` reads JSON and
// nothing else, and the report goes to standard error.
#include <filesystem>
#include <initializer_list>
#include <ostream>

namespace vsil::cli {

std::ostream& reportStream(std::initializer_list<std::filesystem::path> outputs);

}  // namespace vsil::cli
