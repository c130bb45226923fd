// vsil: volume silhouette illustration. Only this file turns errors into exit statuses:
// 2 for bad input (files, flags, parameters), 1 for internal failures.
#include <algorithm>
#include <exception>
#include <iostream>

#include "cli/commands.h"
#include "core/error.h"

int main(int argc, char** argv) {
  CLI::App app{"vsil: silhouettes and illustrations of volume data, rendered offscreen"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "vsil 0.1.0");
  auto commands = vsil::cli::registeredCommands();
  std::stable_sort(commands.begin(), commands.end(),
                   [](const auto& a, const auto& b) { return a.order < b.order; });
  for (const auto& command : commands) command.setup(app);
  try {
    app.parse(argc, argv);
    return 0;
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "vsil: " << e.what() << " (see vsil --help)\n";
    return 2;
  } catch (const vsil::InputError& e) {
    std::cerr << "vsil: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "vsil: internal error: " << e.what() << "\n";
    return 1;
  }
}
