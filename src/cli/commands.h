#pragma once
// Subcommands register themselves: each <name>_command.cpp holds one static
// `CommandRegistration` and main() adds every registered command to the app, sorted by order.
#include <functional>
#include <vector>

#include <CLI/CLI.hpp>

namespace vsil::cli {

using CommandSetup = std::function<void(CLI::App& app)>;

struct CommandRegistration {
  CommandRegistration(int order, CommandSetup setup);
};

// The registered setups, in registration order; main() sorts them by `order`.
struct RegisteredCommand {
  int order;
  CommandSetup setup;
};
std::vector<RegisteredCommand>& registeredCommands();

// Sets up `app` as the vsil tool: one required subcommand, --version, every registered command.
void setUpApp(CLI::App& app);

// When on, a command checks its flags and stops before any work (reading files, rendering,
// writing): the command-line fuzz target (tests/fuzz/fuzz_cli.cpp) parses hostile argument lists
// this way. Each command's callback calls its checks, then returns if validateOnly().
void setValidateOnly(bool on);
bool validateOnly();

}  // namespace vsil::cli
