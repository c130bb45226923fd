#include "serve/render_command_line.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <set>
#include <string_view>

#include "cli/cli_gl_options.h"
#include "cli/cli_parse.h"
#include "cli/cli_postfx_options.h"
#include "cli/cli_volume_options.h"
#include "core/error.h"
#include "core/illustration.h"
#include "core/options.h"
#include "core/rules.h"
#include "core/transfer_function.h"
#include "slicing/technique_table.h"

namespace vsil::serve {

namespace {

// Words a POSIX shell reads as they are; anything else goes in single quotes.
std::string shellWord(const std::string& word) {
  const bool plain = !word.empty() && std::all_of(word.begin(), word.end(), [](unsigned char c) {
    return std::isalnum(c) || std::string_view("_-+=.,:/@%#").find(char(c)) != std::string::npos;
  });
  if (plain && word.front() != '#') return word;
  std::string quoted = "'";
  for (char c : word) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

std::string keyOf(std::string name) {
  std::replace(name.begin(), name.end(), '-', '_');
  return name;
}

// The options that can name a file, and the built-in values the page may give them instead.
const std::map<std::string, std::vector<std::string>>& presetOnlyOptions() {
  static const std::map<std::string, std::vector<std::string>> options{
      {"rules", rulePresetNames()},
      {"style", stylePresetNames()},
      {"tf", transferFunctionPresetNames()},
      {"sphere-map", {"red-blue", "green-red", "green-blue"}},
  };
  return options;
}

const char* kindName(OptionKind kind) {
  static const char* const names[] = {"number", "integer", "choice", "text", "switch", "list"};
  return names[int(kind)];
}

nlohmann::json optionJson(const OptionSpec& spec) {
  nlohmann::json json{{"name", spec.name},
                      {"key", spec.key()},
                      {"kind", kindName(spec.kind)},
                      {"help", spec.help},
                      {"describe", spec.describe()},
                      {"default", nullptr},
                      {"default_note", spec.defaultNote},
                      {"min", nullptr},
                      {"max", nullptr},
                      {"min_exclusive", spec.minExclusive},
                      {"max_exclusive", spec.maxExclusive},
                      {"choices", spec.choices},
                      {"number_count", spec.numberCount}};
  if (spec.defaultValue)
    std::visit([&](const auto& v) { json["default"] = v; }, *spec.defaultValue);
  if (std::isfinite(spec.min)) json["min"] = spec.min;
  if (std::isfinite(spec.max)) json["max"] = spec.max;
  return json;
}

}  // namespace

std::vector<std::string> RenderCommandLine::arguments() const {
  std::vector<std::string> words{input};
  for (const auto& flag : flags) {
    if (flag.values.empty()) words.push_back("--" + flag.name);
    // --name=value: a value starting with '-' stays a value.
    for (const auto& value : flag.values) words.push_back("--" + flag.name + "=" + value);
  }
  return words;
}

std::string RenderCommandLine::shellText(const std::string& out) const {
  std::string text = "vsil render " + shellWord(input);
  for (const auto& flag : flags) {
    if (flag.values.empty()) text += " --" + flag.name;
    for (const auto& value : flag.values) {
      if (!value.empty() && value.front() == '-') {
        text += " " + shellWord("--" + flag.name + "=" + value);
      } else {
        text += " --" + flag.name + " " + shellWord(value);
      }
    }
  }
  return text + " --out " + shellWord(out);
}

const GivenFlag* RenderCommandLine::find(const std::string& name) const {
  const auto it = std::find_if(flags.begin(), flags.end(),
                               [&](const GivenFlag& flag) { return flag.name == name; });
  return it == flags.end() ? nullptr : &*it;
}

CheckedRender checkRenderCommandLine(const RenderCommandLine& line) {
  CheckedRender checked;
  CLI::App app;
  cli::addRenderOptions(app, checked.flags);
  cli::readNumbersAsDecimal(app);  // as the CLI reads them: the recorded command is the render
  std::vector<std::string> arguments = line.arguments();
  std::reverse(arguments.begin(), arguments.end());  // CLI11 takes them last first
  try {
    app.parse(arguments);
  } catch (const CLI::ParseError& e) {
    throw InputError(cli::parseErrorText(e));
  }
  checked.request = cli::toRenderRequest(checked.flags);
  checked.load = cli::toLoadOptions(checked.flags.volume);
  RenderJob::checkRequest(checked.request, checked.load.limits);
  return checked;
}

RenderCommandLine givenRenderFlags(const CLI::App& command,
                                   const std::vector<std::string>& ignored) {
  RenderCommandLine line;
  line.input = cli::kDefaultInput;
  for (const CLI::Option* option : command.get_options()) {
    if (option->count() == 0) continue;
    const std::string name = option->get_single_name();
    if (name == "help" || std::find(ignored.begin(), ignored.end(), name) != ignored.end()) {
      continue;
    }
    if (option->get_positional()) {
      line.input = option->results().front();
    } else if (option->get_expected_min() == 0) {
      line.flags.push_back({name, {}});
    } else {
      line.flags.push_back({name, option->results()});
    }
  }
  return line;
}

PageParameters::PageParameters(RenderCommandLine base) : base_(std::move(base)) {
  std::set<std::string> fixed;
  {
    CLI::App scratch;
    cli::VolumeOptions volume;
    cli::GlOptions gl;
    cli::addVolumeOptions(scratch, volume);
    cli::addGlOptions(scratch, gl);
    for (const CLI::Option* option : scratch.get_options()) fixed.insert(option->get_single_name());
  }
  std::set<std::string> techniqueOptions;
  std::set<std::string> listOptions;
  for (const auto& technique : techniqueTable()) {
    for (const auto& spec : technique.options) {
      techniqueOptions.insert(spec.name);
      if (spec.kind == OptionKind::List) listOptions.insert(spec.name);
    }
  }
  CLI::App app;
  cli::RenderFlags flags;
  cli::addRenderOptions(app, flags);
  for (const CLI::Option* option : app.get_options()) {
    const std::string name = option->get_single_name();
    order_.push_back(name);
    if (option->get_positional() || fixed.count(name)) fixed_.push_back(name);
    if (option->get_positional() || name == "help" || fixed.count(name)) continue;
    Settable settable;
    settable.isSwitch = option->get_expected_min() == 0;
    settable.isList = listOptions.count(name) > 0;
    settable.help = option->get_description();
    settable.defaultText = option->get_default_str();
    settable.technique = techniqueOptions.count(name) > 0;
    settable_.emplace(name, settable);
  }
}

RenderCommandLine PageParameters::apply(
    const std::multimap<std::string, std::string>& parameters) const {
  RenderCommandLine line = base_;
  for (auto it = parameters.begin(); it != parameters.end();
       it = parameters.upper_bound(it->first)) {
    const std::string& key = it->first;
    std::string name = key;
    std::replace(name.begin(), name.end(), '_', '-');
    const auto settable = settable_.find(name);
    if (settable == settable_.end()) {
      if (std::find(fixed_.begin(), fixed_.end(), name) != fixed_.end()) {
        throwInputError(key,
                        "fixed by the server (the input, the volume and the GL flags are "
                        "vsil serve's own)");
      }
      throwInputError(key,
                      "unknown parameter (the page's are vsil render's flags by key, e.g. "
                      "width_near for --width-near)");
    }
    std::vector<std::string> values;
    for (auto [first, last] = parameters.equal_range(key); first != last; ++first) {
      values.push_back(first->second);
    }
    const GivenFlag* own = base_.find(name);
    const auto isOwn = [&](const std::string& value) {
      return own && std::find(own->values.begin(), own->values.end(), value) != own->values.end();
    };
    const std::string flag = "--" + name;
    for (const auto& value : values) {
      // No line breaks or other control characters: the command line goes out in a header.
      if (std::any_of(value.begin(), value.end(),
                      [](unsigned char c) { return c < 0x20 || c == 0x7f; })) {
        throwInputError(flag, "the value holds a control character");
      }
      if (value.empty() || isOwn(value)) continue;
      const auto presets = presetOnlyOptions().find(name);
      if (presets != presetOnlyOptions().end()) {
        const auto& names = presets->second;
        if (std::find(names.begin(), names.end(), value) == names.end()) {
          throwInputError(flag, "'" + value + "': the page names no files (built-in: " +
                                    (names.empty() ? "none" : joined(names)) +
                                    "; give a file on vsil serve's command line)");
        }
      }
      if (value.find_first_of("/\\") != std::string::npos) {
        throwInputError(flag, "'" + value + "': the page names no files");
      }
    }
    line.flags.erase(std::remove_if(line.flags.begin(), line.flags.end(),
                                    [&](const GivenFlag& given) { return given.name == name; }),
                     line.flags.end());
    if (settable->second.isSwitch) {
      if (values.size() > 1) throwInputError(key, "given more than once");
      const std::string& value = values.front();
      if (value == "on" || value == "true" || value == "1") {
        line.flags.push_back({name, {}});
      } else if (!(value.empty() || value == "off" || value == "false" || value == "0")) {
        throwInputError(flag, "'" + value + "' is not on or off");
      }
      continue;
    }
    values.erase(std::remove(values.begin(), values.end(), std::string()), values.end());
    if (values.empty()) continue;
    if (values.size() > 1 && !settable->second.isList) throwInputError(key, "given more than once");
    line.flags.push_back({name, values});
  }
  const auto rank = [&](const GivenFlag& flag) {
    return std::find(order_.begin(), order_.end(), flag.name) - order_.begin();
  };
  std::stable_sort(line.flags.begin(), line.flags.end(),
                   [&](const GivenFlag& a, const GivenFlag& b) { return rank(a) < rank(b); });
  return line;
}

nlohmann::json PageParameters::baseValues() const {
  nlohmann::json values = nlohmann::json::object();
  for (const auto& flag : base_.flags) {
    const auto settable = settable_.find(flag.name);
    if (settable == settable_.end()) continue;
    if (settable->second.isSwitch) {
      values[keyOf(flag.name)] = "on";
    } else if (settable->second.isList) {
      values[keyOf(flag.name)] = flag.values;
    } else {
      values[keyOf(flag.name)] = flag.values.back();
    }
  }
  return values;
}

nlohmann::json PageParameters::optionTable() const {
  nlohmann::json techniques = nlohmann::json::array();
  for (const auto& technique : techniqueTable()) {
    nlohmann::json options = nlohmann::json::array();
    for (const auto& spec : technique.options) options.push_back(optionJson(spec));
    techniques.push_back({{"name", technique.name},
                          {"summary", technique.summary},
                          {"draws_lines", technique.outputs.state},
                          {"options", options}});
  }
  nlohmann::json shared = nlohmann::json::array();
  for (const auto& [name, settable] : settable_) {
    if (settable.technique) continue;
    const bool lineFlag =
        std::ranges::find(cli::lineFlags(), "--" + name) != cli::lineFlags().end();
    shared.push_back({{"name", name},
                      {"key", keyOf(name)},
                      {"kind", settable.isSwitch ? "switch" : "text"},
                      {"help", settable.help},
                      {"default", settable.defaultText},
                      {"line_flag", lineFlag}});
  }
  nlohmann::json presets = nlohmann::json::object();
  for (const auto& [name, names] : presetOnlyOptions()) presets[keyOf(name)] = names;
  return {{"techniques", techniques}, {"shared", shared}, {"presets", presets}};
}

}  // namespace vsil::serve
