#include "cli/commands.h"

#include <algorithm>
#include <string>

#include "cli/cli_parse.h"
#include "core/version.h"
#include "mpi/mpi_world.h"

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
  // Under mpirun with several ranks only render and sweep share their work out; any other
  // command would run once per rank (N servers, every frame N times, N reports): refused once,
  // before its flags are read.
  for (CLI::App* command : app.get_subcommands({})) {
    const std::string name = command->get_name();
    if (name == "render" || name == "sweep") continue;
    command->preparse_callback([name](std::size_t) {
      if (mpi::size() > 1) {
        throw mpi::EveryRankError(
            name + " runs in one process: run it without mpirun (only render and " +
                "sweep share their work across ranks)",
            2);
      }
    });
  }
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
