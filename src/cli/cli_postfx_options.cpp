#include "cli/cli_postfx_options.h"

#include <charconv>

#include "core/error.h"

namespace vsil::cli {

vsil::FillMode parseFillMode(const std::string& text, const std::string& flagName) {
  if (text == "none") return vsil::FillMode::None;
  if (text == "flat") return vsil::FillMode::Flat;
  if (text == "shaded") return vsil::FillMode::Shaded;
  if (text == "tone") return vsil::FillMode::Tone;
  throwInputError(flagName, "'" + text + "' is not a fill mode (none, flat, shaded or tone)");
}

void addPostfxOptions(CLI::App& command, vsil::PostfxOptions& options,
                      std::vector<std::string>& lineFlagsGiven) {
  const auto width = [](const std::string& flag) {
    return [flag](const std::string& text) {
      double value = 0;
      const char* end = text.data() + text.size();
      const auto [stop, error] = std::from_chars(text.data(), end, value);
      if (error == std::errc::result_out_of_range) {
        throwInputError(flag, "'" + text + "' is out of range");
      }
      if (text.empty() || error != std::errc() || stop != end) {
        throwInputError(flag, "'" + text + "' is not a number");
      }
      vsil::WidthLaw::fixed(value).validate(flag);
      return value;
    };
  };
  auto* fixed = command.add_option_function<std::string>(
      "--width",
      [&options, parse = width("--width")](const std::string& text) {
        options.width = vsil::WidthLaw::fixed(parse(text));
      },
      "total line width in pixels (>= 1; 1 = the one-pixel silhouettes)");
  auto* near = command.add_option_function<std::string>(
      "--width-near",
      [&options, parse = width("--width-near")](const std::string& text) {
        options.width.near = parse(text);
      },
      "line width at normalized depth 0 (depth-adaptive, with --width-far)");
  auto* far = command.add_option_function<std::string>(
      "--width-far",
      [&options, parse = width("--width-far")](const std::string& text) {
        options.width.far = parse(text);
      },
      "line width at normalized depth 1 (depth-adaptive, with --width-near)");
  near->needs(far);
  far->needs(near);
  fixed->excludes(near);
  fixed->excludes(far);

  command.add_option_function<std::string>(
      "--line-color",
      [&options](const std::string& text) {
        options.lineColor = vsil::parseColor(text, "--line-color");
      },
      "line colour: a name (black, white, red, ...) or #rgb, #rrggbb, #rrggbbaa");
  command.add_option_function<std::string>(
      "--background",
      [&options](const std::string& text) {
        options.background = vsil::parseColor(text, "--background");
      },
      "background colour: a name or #rgb, #rrggbb, #rrggbbaa (transparent allowed)");
  command.add_option_function<std::string>(
      "--fill",
      [&options](const std::string& text) { options.fill = parseFillMode(text, "--fill"); },
      "what filled (inside) pixels show: none, flat, shaded (by |n.v|) or tone (tone shading "
      "and distance blending; --param, --light)");
  command.add_option_function<std::string>(
      "--fill-color",
      [&options](const std::string& text) {
        options.fillColor = vsil::parseColor(text, "--fill-color");
      },
      "colour of --fill flat / shaded / tone");
  for (const std::string& flag : lineFlags()) {
    command.get_option(flag)->each(
        [&lineFlagsGiven, flag](const std::string&) { lineFlagsGiven.push_back(flag); });
  }
}

const std::vector<std::string>& lineFlags() {
  static const std::vector<std::string> flags = {"--width",      "--width-near", "--width-far",
                                                 "--line-color", "--fill",       "--fill-color"};
  return flags;
}

}  // namespace vsil::cli
