#include "cli/commands.h"

namespace vsil::cli {

std::vector<RegisteredCommand>& registeredCommands() {
  static std::vector<RegisteredCommand> commands;
  return commands;
}

CommandRegistration::CommandRegistration(int order, CommandSetup setup) {
  registeredCommands().push_back({order, std::move(setup)});
}

}  // namespace vsil::cli
