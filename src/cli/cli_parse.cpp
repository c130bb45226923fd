#include "cli/cli_parse.h"

#include <algorithm>
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

void readNumbersAsDecimal(CLI::App& app) {
  for (CLI::Option* option : app.get_options()) {
    const std::string type = option->get_type_name();
    const bool whole = type == "INT" || type == "UINT";
    if (!whole && type != "FLOAT") continue;
    const std::string flag = option->get_name();
    option->transform([flag, whole](std::string text) {
      const std::size_t digits = text.starts_with('+') || text.starts_with('-') ? 1 : 0;
      const std::string_view number = std::string_view(text).substr(digits);
      if (number.starts_with("0x") || number.starts_with("0X")) {
        throwInputError(flag + " " + text, "is hexadecimal; write the number in decimal");
      }
      if (!whole) return text;
      const bool decimal = !number.empty() && std::all_of(number.begin(), number.end(), [](char c) {
        return c >= '0' && c <= '9';
      });
      if (!decimal) return text;  // CLI11 refuses it, naming the flag
      const std::size_t firstDigit = std::min(number.find_first_not_of('0'), number.size() - 1);
      const std::string_view significant = number.substr(firstDigit);
      long long value = 0;
      const auto result =
          std::from_chars(significant.data(), significant.data() + significant.size(), value);
      if (result.ec == std::errc::result_out_of_range) {
        throwInputError(flag + " " + text, "is beyond every whole number the flag takes");
      }
      return text.substr(0, digits) + std::string(significant);
    });
  }
  for (CLI::App* command : app.get_subcommands({})) readNumbersAsDecimal(*command);
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
