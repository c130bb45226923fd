#include "cli/cli_report.h"

#include <iostream>

#include "core/atomic_file.h"

namespace vsil::cli {

std::ostream& reportStream(std::initializer_list<std::filesystem::path> outputs) {
  for (const std::filesystem::path& output : outputs) {
    if (!output.empty() && namesStandardOutput(output)) return std::cerr;
  }
  return std::cout;
}

}  // namespace vsil::cli
