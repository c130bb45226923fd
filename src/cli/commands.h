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

}  // namespace vsil::cli
