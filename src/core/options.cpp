#include "core/options.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <utility>

#include <nlohmann/json.hpp>

#include "core/error.h"

namespace vsil {

namespace {

// What a value of each kind is, in OptionKind's order, for messages.
const char* kindName(OptionKind kind) {
  static const char* const names[] = {"a number", "a whole number", "a name",
                                      "text",     "on or off",      "a list of texts"};
  return names[int(kind)];
}

bool holdsKind(const OptionValue& value, OptionKind kind) {
  switch (kind) {
    case OptionKind::Number:
    case OptionKind::Integer:
      return std::holds_alternative<double>(value);
    case OptionKind::Choice:
    case OptionKind::Text:
      return std::holds_alternative<std::string>(value);
    case OptionKind::Switch:
      return std::holds_alternative<bool>(value);
    case OptionKind::List:
      return std::holds_alternative<std::vector<std::string>>(value);
  }
  return false;
}

// "> 0", "in [0, 1]", "in (0, 64]" — empty for an unbounded number.
std::string describeRange(const OptionSpec& spec) {
  const bool hasMin = std::isfinite(spec.min), hasMax = std::isfinite(spec.max);
  if (hasMin && hasMax) {
    return std::string("in ") + (spec.minExclusive ? "(" : "[") + formatNumber(spec.min) + ", " +
           formatNumber(spec.max) + (spec.maxExclusive ? ")" : "]");
  }
  if (hasMin) return (spec.minExclusive ? "> " : ">= ") + formatNumber(spec.min);
  if (hasMax) return (spec.maxExclusive ? "< " : "<= ") + formatNumber(spec.max);
  return "";
}

std::string valueText(const OptionValue& value) {
  if (const auto* b = std::get_if<bool>(&value)) return *b ? "on" : "off";
  if (const auto* d = std::get_if<double>(&value)) return formatNumber(*d);
  if (const auto* s = std::get_if<std::string>(&value)) return *s;
  return joined(std::get<std::vector<std::string>>(value), " ");
}

}  // namespace

std::optional<std::vector<double>> parseNumberList(std::string_view text, int count) {
  std::vector<double> numbers;
  while (true) {
    const std::size_t comma = text.find(',');
    const std::string_view item = text.substr(0, comma);
    double number = 0;
    const auto [ptr, ec] = std::from_chars(item.data(), item.data() + item.size(), number);
    if (item.empty() || ec != std::errc() || ptr != item.data() + item.size() ||
        !std::isfinite(number)) {
      return std::nullopt;
    }
    numbers.push_back(number);
    if (comma == std::string_view::npos) break;
    text.remove_prefix(comma + 1);
  }
  if (count > 0 && int(numbers.size()) != count) return std::nullopt;
  return numbers;
}

const std::string* givenText(const OptionValues& given, std::string_view name) {
  const auto it = given.find(name);
  return it == given.end() ? nullptr : std::get_if<std::string>(&it->second);
}

bool isInlineSource(std::string_view text) {
  const auto first = text.find_first_not_of(" \t\r\n");
  const auto last = text.find_last_not_of(" \t\r\n");
  const bool list = first != std::string_view::npos && text[first] == '[' && text[last] == ']';
  return list || text.find('{') != std::string_view::npos;
}

std::string formatNumber(double number) {
  char buffer[32];
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, number);
  return std::string(buffer, end);  // 32 chars hold any double's shortest form
}

std::string joined(const std::vector<std::string>& items, const std::string& separator) {
  std::string text;
  for (const auto& item : items) text += (text.empty() ? "" : separator) + item;
  return text;
}

std::string formatNumberList(const std::vector<double>& numbers) {
  std::string text;
  for (double number : numbers) text += (text.empty() ? "" : ",") + formatNumber(number);
  return text;
}

OptionSpec OptionSpec::number(std::string name, double defaultValue, std::string help) {
  OptionSpec spec;
  spec.name = std::move(name);
  spec.kind = OptionKind::Number;
  spec.defaultValue = defaultValue;
  spec.help = std::move(help);
  return spec;
}

OptionSpec OptionSpec::integer(std::string name, int defaultValue, std::string help) {
  OptionSpec spec = number(std::move(name), defaultValue, std::move(help));
  spec.kind = OptionKind::Integer;
  return spec;
}

OptionSpec OptionSpec::choice(std::string name, std::string defaultValue,
                              std::vector<std::string> choices, std::string help) {
  OptionSpec spec;
  spec.name = std::move(name);
  spec.kind = OptionKind::Choice;
  spec.defaultValue = std::move(defaultValue);
  spec.choices = std::move(choices);
  spec.help = std::move(help);
  return spec;
}

OptionSpec OptionSpec::text(std::string name, std::string help) {
  OptionSpec spec;
  spec.name = std::move(name);
  spec.kind = OptionKind::Text;
  spec.help = std::move(help);
  return spec;
}

OptionSpec OptionSpec::list(std::string name, std::string help) {
  OptionSpec spec = text(std::move(name), std::move(help));
  spec.kind = OptionKind::List;
  return spec;
}

OptionSpec OptionSpec::flag(std::string name, std::string help) {
  OptionSpec spec = text(std::move(name), std::move(help));
  spec.kind = OptionKind::Switch;
  spec.defaultValue = false;
  return spec;
}

OptionSpec& OptionSpec::above(double bound) {
  min = bound;
  minExclusive = true;
  return *this;
}
OptionSpec& OptionSpec::atLeast(double bound) {
  min = bound;
  minExclusive = false;
  return *this;
}
OptionSpec& OptionSpec::atMost(double bound) {
  max = bound;
  maxExclusive = false;
  return *this;
}

OptionSpec& OptionSpec::below(double bound) {
  max = bound;
  maxExclusive = true;
  return *this;
}

OptionSpec& OptionSpec::validatedBy(std::function<void(const OptionValue&)> check) {
  validate = std::move(check);
  return *this;
}

OptionSpec& OptionSpec::holdsNumbers(int count) {
  numberCount = count;
  return *this;
}

std::string OptionSpec::key() const {
  std::string k = name;
  std::replace(k.begin(), k.end(), '-', '_');
  return k;
}

OptionValue OptionSpec::parse(const std::string& text) const {
  // An empty value (--tf '', a shell variable left unset) is refused, never read as the flag
  // left out: that would render something else than asked without a word.
  if (text.empty() && kind != OptionKind::Switch) {
    throwInputError(flag(), "is empty: give a value, or leave the flag out");
  }
  OptionValue value;
  switch (kind) {
    case OptionKind::Number:
    case OptionKind::Integer: {
      double number = 0;
      const char* end = text.data() + text.size();
      const auto [ptr, ec] = std::from_chars(text.data(), end, number);
      if (ec == std::errc::result_out_of_range) {
        throwInputError(flag(), "'" + text + "' is out of range");
      }
      if (ec != std::errc() || ptr != end) {
        throwInputError(flag(), "'" + text + "' is not " + kindName(kind));
      }
      value = number;
      break;
    }
    case OptionKind::Switch:
      if (text == "on" || text == "true" || text == "1") {
        value = true;
      } else if (text == "off" || text == "false" || text == "0") {
        value = false;
      } else {
        throwInputError(flag(), "'" + text + "' is not on or off");
      }
      break;
    case OptionKind::List:
      value = std::vector<std::string>{text};
      break;
    case OptionKind::Choice:
    case OptionKind::Text:
      value = text;
      break;
  }
  check(value);
  return value;
}

void requireSinglePrecision(const std::string& where, std::initializer_list<double> numbers) {
  for (double number : numbers) {
    if (!(std::abs(number) <= double(std::numeric_limits<float>::max()))) {
      throwInputError(where, "must be within +-3.4e38 (the GPU computes in single precision)");
    }
  }
}

void OptionSpec::check(const OptionValue& value) const {
  if (!holdsKind(value, kind)) throwInputError(flag(), std::string("must be ") + kindName(kind));
  if (kind == OptionKind::Number || kind == OptionKind::Integer) {
    const double number = std::get<double>(value);
    if (!std::isfinite(number)) throwInputError(flag(), "must be a finite number");
    if (kind == OptionKind::Integer && number != std::floor(number)) {
      throwInputError(flag(), "must be a whole number");
    }
    const bool belowMin = minExclusive ? !(number > min) : !(number >= min);
    const bool aboveMax = maxExclusive ? !(number < max) : !(number <= max);
    if (belowMin || aboveMax) {
      throwInputError(flag(),
                      "must be " + describeRange(*this) + " (got " + formatNumber(number) + ")");
    }
    requireSinglePrecision(flag(), {number});  // after the range, which says more where given
  }
  if (kind == OptionKind::Text && numberCount > 0) {
    const std::string& text = std::get<std::string>(value);
    const auto numbers = text.empty() ? std::nullopt : parseNumberList(text, numberCount);
    if (!text.empty() && !numbers) {
      throwInputError(flag(), "'" + text + "' is not " + std::to_string(numberCount) +
                                  " numbers separated by commas");
    }
    for (double number : numbers.value_or(std::vector<double>{})) {
      requireSinglePrecision(flag() + ": '" + text + "'", {number});
    }
  }
  if (kind == OptionKind::Choice) {
    const std::string& name = std::get<std::string>(value);
    if (std::find(choices.begin(), choices.end(), name) == choices.end()) {
      throwInputError(flag(),
                      "unknown value '" + name + "' (known: " + joined(choices, ", ") + ")");
    }
  }
  if (validate) validate(value);
}

std::string OptionSpec::describe() const {
  std::vector<std::string> parts;
  if (defaultValue) {
    parts.push_back("default " + valueText(*defaultValue) +
                    (defaultNote.empty() ? "" : " (" + defaultNote + ")"));
  } else if (!defaultNote.empty()) {
    parts.push_back("default " + defaultNote);
  }
  if (kind == OptionKind::Choice) parts.push_back(joined(choices, " | "));
  const std::string range = describeRange(*this);
  if (!range.empty() && (kind == OptionKind::Number || kind == OptionKind::Integer)) {
    parts.push_back(range);
  }
  return joined(parts, ", ");
}

void checkOptions(const std::vector<OptionSpec>& specs, const OptionValues& values,
                  const std::string& owner) {
  for (const auto& given : values) {
    const std::string& name = given.first;  // not a structured binding: clang 14 cannot capture one
    const auto it = std::find_if(specs.begin(), specs.end(),
                                 [&](const OptionSpec& spec) { return spec.name == name; });
    if (it == specs.end()) {
      std::vector<std::string> flags;
      for (const auto& spec : specs) flags.push_back(spec.flag());
      throwInputError("--" + name, "not an option of " + owner + " (its options: " +
                                       (flags.empty() ? "none" : joined(flags, ", ")) + ")");
    }
    it->check(given.second);
  }
}

OptionReader::OptionReader(const std::vector<OptionSpec>& specs, const OptionValues& values,
                           DerivedDefaults derived)
    : specs_(specs), derived_(derived) {
  for (const auto& spec : specs) {
    const auto given = values.find(spec.name);
    if (given != values.end()) {
      resolved_.emplace(spec.name, given->second);
      given_.push_back(spec.name);
    } else if (spec.defaultValue) {
      resolved_.emplace(spec.name, *spec.defaultValue);
    } else if (spec.derived == OptionSpec::Derived::VolumeIso) {
      resolved_.emplace(spec.name, derived.iso);
    } else if (spec.derived == OptionSpec::Derived::RangeFraction) {
      resolved_.emplace(spec.name, spec.rangeFraction * derived.valueRangeWidth);
    } else if (spec.kind == OptionKind::List) {
      resolved_.emplace(spec.name, std::vector<std::string>{});
    } else if (spec.kind == OptionKind::Text) {
      resolved_.emplace(spec.name, std::string());
    } else if (spec.kind == OptionKind::Number && !spec.defaultNote.empty()) {
      // Not given, and no value stands for that (OptionSpec::defaultValue).
    } else {
      throw std::logic_error("option --" + spec.name + " has no default and none is derived");
    }
  }
}

const OptionValue& OptionReader::value(std::string_view name) const {
  const auto it = resolved_.find(name);
  if (it == resolved_.end()) {
    throw std::logic_error("OptionReader: --" + std::string(name) +
                           " is not declared, or has no value when not given (check given())");
  }
  return it->second;
}

double OptionReader::number(std::string_view name) const {
  return std::get<double>(value(name));
}
int OptionReader::integer(std::string_view name) const {
  return int(std::get<double>(value(name)));
}
bool OptionReader::enabled(std::string_view name) const {
  return std::get<bool>(value(name));
}
const std::string& OptionReader::text(std::string_view name) const {
  return std::get<std::string>(value(name));
}
const std::vector<std::string>& OptionReader::list(std::string_view name) const {
  return std::get<std::vector<std::string>>(value(name));
}
bool OptionReader::given(std::string_view name) const {
  return std::find(given_.begin(), given_.end(), name) != given_.end();
}

nlohmann::json OptionReader::toJson() const {
  nlohmann::json json = nlohmann::json::object();
  for (const auto& spec : specs_) {
    const auto it = resolved_.find(spec.name);
    if (it == resolved_.end()) {
      json[spec.key()] = nullptr;  // an option whose absence is its default
      continue;
    }
    std::visit([&](const auto& v) { json[spec.key()] = v; }, it->second);
  }
  return json;
}

}  // namespace vsil
