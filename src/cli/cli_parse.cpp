#include "cli/cli_parse.h"

#include <charconv>
#include <cstdlib>
#include <limits>

#include <CLI/CLI.hpp>

#include "core/error.h"

namespace vsil::cli {
namespace {

bool parseInt(const std::string& text, int& value) {
  if (text.empty() || text.size() > 9) return false;
  for (char c : text) {
    if (c < '0' || c > '9') return false;
  }
  value = std::atoi(text.c_str());
  return true;
}

}  // namespace

CLI::Option* nonEmpty(CLI::Option* option) {
  const std::string flag = option->get_name();
  return option->each([flag](const std::string& value) {
    if (value.empty()) throwInputError(flag, "is empty: give a value, or leave the flag out");
  });
}

void refuseWholeNumbersBeyondRange(CLI::App& app) {
  for (CLI::Option* option : app.get_options()) {
    const std::string type = option->get_type_name();
    if (type != "INT" && type != "UINT") continue;
    const std::string flag = option->get_name();
    option->each([flag](const std::string& text) {
      long long value = 0;
      const char* end = text.data() + text.size();
      const auto result =
          std::from_chars(text.data() + (text.starts_with('+') ? 1 : 0), end, value);
      if (result.ec == std::errc::result_out_of_range && result.ptr == end) {
        throwInputError(flag + " " + text, "is beyond every whole number the flag takes");
      }
    });
  }
  for (CLI::App* command : app.get_subcommands({})) refuseWholeNumbersBeyondRange(*command);
}

glm::ivec2 parseSize(const std::string& flag, const std::string& text) {
  const auto x = text.find_first_of("xX");
  glm::ivec2 size;
  if (x == std::string::npos || !parseInt(text.substr(0, x), size.x) ||
      !parseInt(text.substr(x + 1), size.y) || size.x < 1 || size.y < 1) {
    throw InputError(flag + ": '" + text + "' is not a size WxH with positive integers");
  }
  return size;
}

std::string parseErrorText(const CLI::ParseError& error) {
  const std::string text = error.what();
  const std::string conversion = "Could not convert: ";
  if (text.starts_with(conversion)) {
    const std::size_t equals = text.find(" = ", conversion.size());
    if (equals != std::string::npos) {
      return text.substr(conversion.size(), equals - conversion.size()) + ": '" +
             text.substr(equals + 3) + "' is not a value it takes";
    }
  }
  const std::size_t atMostOne = text.find(": At Most 1 required but received ");
  if (atMostOne != std::string::npos) return text.substr(0, atMostOne) + ": given more than once";
  return text;
}

}  // namespace vsil::cli
