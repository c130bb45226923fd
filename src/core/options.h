#pragma once
// Declared options, in the spirit of pbrt-v4's ParameterDictionary: each technique declares its
// options once (name, kind, default, range, help; slicing/technique_table.h), and every caller —
// the CLI's flags and help, the metadata, the benchmark, the Python keywords — reads those
// declarations. A technique reads its values by name through OptionReader; values given for an
// option it does not declare are reported (checkOptions), never silently ignored.
#include <functional>
#include <initializer_list>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include <nlohmann/json_fwd.hpp>

namespace vsil {

enum class OptionKind {
  Number,   // a finite real within [min, max] (ends open where said)
  Integer,  // a whole number within [min, max]
  Choice,   // one of `choices`
  Text,     // any text (a file name, a list the technique parses itself)
  Switch,   // on or off; given on the command line without a value
  List,     // text given any number of times (e.g. --light AZ,EL twice)
};

using OptionValue = std::variant<bool, double, std::string, std::vector<std::string>>;

struct OptionSpec {
  std::string name;  // the flag without "--" ("ra-exponent"); key() for JSON and Python
  OptionKind kind = OptionKind::Number;
  std::string help;
  // The value when none is given. Unset: derived (see `derived`; defaultNote says how for the
  // help), or empty for Text and List; for a Number neither declared nor derived, nothing:
  // leaving it out is its own behaviour (defaultNote says which; semantic's flatness), read
  // only where OptionReader::given, null in toJson, None in Python.
  std::optional<OptionValue> defaultValue;
  // VolumeIso: the volume's default iso value. RangeFraction: `rangeFraction` of the width of
  // the volume's value range (a tolerance in data units that scales with the data).
  enum class Derived { None, VolumeIso, RangeFraction };
  Derived derived = Derived::None;
  double rangeFraction = 0.0;
  // How a derived default is found, for the help; beside a declared default, where it gives way.
  std::string defaultNote;
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool minExclusive = false;
  bool maxExclusive = false;
  std::vector<std::string> choices;
  // Checks the value further (a Text or List the technique parses itself: effect names,
  // NAME=VALUE lists, colours); throws InputError naming the flag. Empty: no further check.
  std::function<void(const OptionValue&)> validate;
  // Text holding this many numbers separated by commas ("X,Y,Z": a position, a colour); 0: any
  // text. Checked like a value's range; `vsil animate --sweep` interpolates it componentwise.
  int numberCount = 0;

  // Declaring an option in one expression:
  //   OptionSpec::number("ra-exponent", 8.0, "exponent k of the line test").above(0)
  static OptionSpec number(std::string name, double defaultValue, std::string help);
  static OptionSpec integer(std::string name, int defaultValue, std::string help);
  static OptionSpec choice(std::string name, std::string defaultValue,
                           std::vector<std::string> choices, std::string help);
  static OptionSpec text(std::string name, std::string help);  // default: empty
  static OptionSpec list(std::string name, std::string help);  // default: none given
  static OptionSpec flag(std::string name, std::string help);  // default: off
  OptionSpec& above(double bound);                             // > bound
  OptionSpec& atLeast(double bound);                           // >= bound
  OptionSpec& atMost(double bound);                            // <= bound
  OptionSpec& below(double bound);                             // < bound
  OptionSpec& validatedBy(std::function<void(const OptionValue&)> check);
  // Text: `count` numbers separated by commas (numberCount).
  OptionSpec& holdsNumbers(int count);

  // "ra-exponent" → "ra_exponent": the metadata key and the Python keyword.
  std::string key() const;
  std::string flag() const { return "--" + name; }
  // Parses one value as given on the command line and checks it; InputError naming the flag.
  OptionValue parse(const std::string& text) const;
  // Checks a value of any origin (parsed, Python, a style file): its type and range.
  void check(const OptionValue& value) const;
  // "default 8, > 0" — for help texts.
  std::string describe() const;
};

// "X,Y,Z" with finite numbers, exactly `count` of them (any count ≥ 1 when `count` is 0); nothing
// when the text is not such a list. formatNumberList writes the shortest text that reads back
// to the same doubles.
std::optional<std::vector<double>> parseNumberList(std::string_view text, int count = 0);
// Options reach the GPU as 32-bit floats, where a larger number turns infinite (a --window of
// -1e308,1e308 drew an all-black image without a word): InputError "<where>: must be within
// +-3.4e38 ..." for a number beyond. OptionSpec::check applies it to numbers and number lists.
void requireSinglePrecision(const std::string& where, std::initializer_list<double> numbers);
std::string formatNumberList(const std::vector<double>& numbers);
// The shortest text that reads back to the same double (what error messages quote).
std::string formatNumber(double number);
// The items with `separator` between them (what messages list: "known: a, b, c").
std::string joined(const std::vector<std::string>& items, const std::string& separator = ", ");
// Whether a --tf, --style or --rules value is the content itself (a JSON list or object, rule
// text) rather than a preset name or a file: it holds '{', which no preset name holds and every
// transfer function, style and rule base does (a point, an object, an attribute block), or it
// is a JSON list ("[ ... ]", also the empty one, refused then for what it lacks). The Python
// package passes tf=[{...}], style={...} and rule text this way.
bool isInlineSource(std::string_view text);

// Option values by name, as given (defaults are not stored here).
using OptionValues = std::map<std::string, OptionValue, std::less<>>;

// The text an option was given, or null where it was not given or is not text.
const std::string* givenText(const OptionValues& given, std::string_view name);

// Throws InputError for a value whose name `specs` do not declare ("--ra-exponent: not an option
// of technique 'silhouette' (its options: --iso, --pipeline)") or whose value does not check.
void checkOptions(const std::vector<OptionSpec>& specs, const OptionValues& values,
                  const std::string& owner);

// What a technique reads: its declared options, the given values, and the facts derived
// defaults come from.
struct DerivedDefaults {
  double iso = 0.5;              // the volume's default iso value (core/volume.h defaultIso)
  double valueRangeWidth = 1.0;  // max − min of the volume's samples
  double valueMin = 0.0;         // min of the volume's samples
  // The high end of the default grey window of the MIP family, whose low end is `iso`
  // (core/volume.h derivedDefaults).
  double windowHigh = 1.0;
};

// A technique's options resolved: the given values, else the declared or derived defaults.
class OptionReader {
 public:
  OptionReader() = default;
  OptionReader(const std::vector<OptionSpec>& specs, const OptionValues& values,
               DerivedDefaults derived = {});
  double number(std::string_view name) const;
  int integer(std::string_view name) const;
  bool enabled(std::string_view name) const;             // a Switch
  const std::string& text(std::string_view name) const;  // Choice or Text
  const std::vector<std::string>& list(std::string_view name) const;
  bool given(std::string_view name) const;
  // The facts the derived defaults came from (for defaults no single option holds: the MIP
  // family's window).
  const DerivedDefaults& derived() const { return derived_; }
  // Every declared option with the value used, by key(); for the metadata.
  nlohmann::json toJson() const;

 private:
  const OptionValue& value(std::string_view name) const;

  std::vector<OptionSpec> specs_;
  OptionValues resolved_;
  std::vector<std::string> given_;
  DerivedDefaults derived_;
};

}  // namespace vsil
