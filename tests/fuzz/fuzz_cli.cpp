// The command line: CLI11's parse and every command's flag checks (sizes, pairs, colours,
// widths, raw layouts, --max-memory, the render limits), stopping before any file is read or
// frame rendered (cli::setValidateOnly). Input: the arguments after `vsil`, separated by NUL.
#include <CLI/CLI.hpp>

#include "cli/commands.h"
#include "fuzz_target.h"

VSIL_FUZZ_TARGET(cli) {
  std::vector<std::string> arguments{"vsil"};
  std::string current;
  for (std::uint8_t byte : bytes) {
    if (byte == 0) {
      arguments.push_back(current);
      current.clear();
    } else {
      current.push_back(char(byte));
    }
  }
  arguments.push_back(current);
  std::vector<const char*> argv;
  for (const std::string& argument : arguments) argv.push_back(argument.c_str());

  vsil::cli::setValidateOnly(true);
  CLI::App app{"vsil"};
  vsil::cli::setUpApp(app);
  try {
    app.parse(int(argv.size()), argv.data());
  } catch (const CLI::ParseError&) {
    // main() answers these with exit status 2 (or help/version text, exit 0).
  }
}
