#include "cli/cli_technique_options.h"

#include <map>
#include <stdexcept>

#include "slicing/technique_table.h"

namespace vsil::cli {

namespace {

// "[silhouette, rightangle] iso value in the data's own units (default ...)"; where the
// techniques' defaults differ, each one's: "(silhouette: default tiles, ...; rightangle: ...)".
std::string helpText(const std::vector<const OptionSpec*>& specs,
                     const std::vector<std::string>& users) {
  std::string owners;
  for (const auto& name : users) owners += (owners.empty() ? "" : ", ") + name;
  std::string details = specs.front()->describe();
  for (const OptionSpec* spec : specs) {
    if (spec->describe() == details) continue;
    details.clear();
    for (std::size_t i = 0; i < specs.size(); ++i) {
      details += (i ? "; " : "") + users[i] + ": " + specs[i]->describe();
    }
    break;
  }
  return "[" + owners + "] " + specs.front()->help + (details.empty() ? "" : " (" + details + ")");
}

// The value's name in the help, in OptionKind's order (a Switch takes none).
const char* typeName(OptionKind kind) {
  static const char* const names[] = {"NUMBER", "INTEGER", "NAME", "TEXT", "", "TEXT"};
  return names[int(kind)];
}

}  // namespace

void addTechniqueOptions(CLI::App& command, std::string& technique, OptionValues& values) {
  std::string names;
  for (const auto& name : techniqueNames()) names += (names.empty() ? "" : " | ") + name;
  command.add_option("--technique", technique, names)->capture_default_str();

  // Each option once, by name, with the techniques that read it; a name two techniques declare
  // must mean the same, up to its default (tests/cli checks the table for that). A value is
  // parsed and checked by the first declaration, the technique's own when it renders.
  std::map<std::string, std::pair<std::vector<const OptionSpec*>, std::vector<std::string>>>
      options;
  std::vector<std::string> order;
  for (const auto& info : techniqueTable()) {
    for (const auto& spec : info.options) {
      auto [it, added] = options.try_emplace(spec.name);
      if (added) order.push_back(spec.name);
      it->second.first.push_back(&spec);
      it->second.second.push_back(info.name);
    }
  }
  const std::string group = "Technique options";
  for (const auto& name : order) {
    const auto& [specs, users] = options.at(name);
    const OptionSpec* spec = specs.front();
    const std::string help = helpText(specs, users);
    CLI::Option* option = nullptr;
    switch (spec->kind) {
      case OptionKind::Switch:
        option = command.add_flag_function(
            spec->flag(), [&values, name](std::int64_t) { values[name] = true; }, help);
        break;
      case OptionKind::List:
        option = command
                     .add_option_function<std::vector<std::string>>(
                         spec->flag(),
                         [&values, spec = *spec](const std::vector<std::string>& texts) {
                           std::vector<std::string> all;
                           for (const auto& text : texts) {
                             const auto parsed =
                                 std::get<std::vector<std::string>>(spec.parse(text));
                             all.insert(all.end(), parsed.begin(), parsed.end());
                           }
                           values[spec.name] = all;
                         },
                         help)
                     ->expected(1)
                     ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
        break;
      default:
        option = command.add_option_function<std::string>(
            spec->flag(),
            [&values, spec = *spec](const std::string& text) {
              values[spec.name] = spec.parse(text);
            },
            help);
        break;
    }
    option->group(group);
    if (spec->kind != OptionKind::Switch) option->type_name(typeName(spec->kind));
  }
}

}  // namespace vsil::cli
