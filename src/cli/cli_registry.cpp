#include "cli/commands.h"

#include <algorithm>
#include <string>

#include "cli/cli_parse.h"
#include "core/version.h"

namespace vsil::cli {

std::vector<RegisteredCommand>& registeredCommands() {
  static std::vector<RegisteredCommand> commands;
  return commands;
}

CommandRegistration::CommandRegistration(int order, CommandSetup setup) {
  registeredCommands().push_back({order, std::move(setup)});
}

void setUpApp(CLI::App& app) {
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("vsil ") + kVsilVersion);
  auto commands = registeredCommands();
  std::stable_sort(commands.begin(), commands.end(),
                   [](const auto& a, const auto& b) { return a.order < b.order; });
  for (const auto& command : commands) command.setup(app);
  readNumbersAsDecimal(app);
}

namespace {
bool validateOnlyFlag = false;
}

void setValidateOnly(bool on) {
  validateOnlyFlag = on;
}
bool validateOnly() {
  return validateOnlyFlag;
}

}  // namespace vsil::cli
