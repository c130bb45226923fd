#include "core/rules.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <numeric>
#include <optional>

#include "core/error.h"
#include "core/limits.h"
#include "core/options.h"
#include "io/file_access.h"

namespace vsil {

// The presets (src/CMakeLists.txt embeds src/core/rules/*.rules).
std::string_view embeddedRuleSource(std::string_view path);
std::vector<std::string_view> embeddedRulePaths();

namespace {

// ---------------------------------------------------------------------------------------------
// Names and numbers as the file writes them.

constexpr std::array<const char*, kAttributeSourceCount> kSourceNames = {
    "data",       "gradient", "cursor_distance", "plane_distance", "image_distance",
    "view_angle", "time"};

constexpr std::array<const char*, 4> kShapeNames = {"trapezoid", "triangle", "gauss", "points"};

constexpr std::array<const char*, 13> kKeywords = {
    "attribute", "from", "style", "priority", "flatness", "spheres", "rule",
    "if",        "then", "is",    "and",      "or",       "not"};

bool isKeyword(std::string_view word) {
  return std::find(kKeywords.begin(), kKeywords.end(), word) != kKeywords.end();
}

std::string joinNames(const std::vector<std::string>& names) {
  std::string list;
  for (const auto& name : names) list += (list.empty() ? "" : ", ") + name;
  return list;
}

template <typename Item>
std::string joinItemNames(const std::vector<Item>& items) {
  std::vector<std::string> names;
  for (const auto& item : items) names.push_back(item.name);
  return joinNames(names);
}

// A name or string in a message: quoted, at most ~40 bytes, non-printable bytes as \xHH.
std::string inQuotes(std::string_view text, char quote = '\'') {
  constexpr std::size_t kMax = 40;
  std::string out(1, quote);
  for (std::size_t i = 0; i < text.size() && i < kMax; ++i) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if (c < 0x20 || c >= 0x7f) {
      constexpr char kHex[] = "0123456789abcdef";
      out += "\\x";
      out += kHex[c >> 4];
      out += kHex[c & 15];
    } else {
      out += char(c);
    }
  }
  if (text.size() > kMax) out += "...";
  return out + quote;
}

// ---------------------------------------------------------------------------------------------
// Membership functions.

double trapezoidAt(double x, double a, double b, double c, double d) {
  if (x < a || x > d) return 0.0;
  if (x < b) return (x - a) / (b - a);  // a <= x < b: b > a
  if (x <= c) return 1.0;
  return (d - x) / (d - c);  // c < x <= d: d > c
}

double pointsAt(double x, const std::vector<glm::dvec2>& points) {
  if (x <= points.front().x) return points.front().y;
  if (x >= points.back().x) return points.back().y;
  const auto above = std::upper_bound(points.begin(), points.end(), x,
                                      [](double v, const glm::dvec2& p) { return v < p.x; });
  const glm::dvec2 low = *(above - 1);
  const glm::dvec2 high = *above;  // high.x > low.x: x strictly increases
  const double t = (x - low.x) / (high.x - low.x);
  return low.y + t * (high.y - low.y);
}

// Midpoints of this many equal intervals of [0, 1] integrate the style values (tables, checks):
// a piecewise linear shape's error is below 1e-8 of its integral, a narrowest Gaussian
// (sd 0.001) is sampled 16 times per sd.
constexpr int kIntegrationSteps = 16384;

double integralOnUnit(const MembershipFunction& function) {
  double sum = 0.0;
  for (int m = 0; m < kIntegrationSteps; ++m) sum += function.at((m + 0.5) / kIntegrationSteps);
  return sum / kIntegrationSteps;
}

// The largest degree on [0, 1], exactly: piecewise linear shapes peak at a corner (or an end),
// a Gaussian at its mean clamped into [0, 1].
double maximumOnUnit(const MembershipFunction& function) {
  std::vector<double> xs = {0.0, 1.0};
  if (function.shape == Shape::Points) {
    for (const auto& p : function.points) xs.push_back(p.x);
  } else {
    xs.insert(xs.end(), function.parameters.begin(), function.parameters.end());
  }
  double peak = 0.0;
  for (double x : xs) {
    if (x >= 0.0 && x <= 1.0) peak = std::max(peak, function.at(x));
  }
  return peak;
}

// A style value's integral on [0, 1] below this is refused: the centroid divides by it.
constexpr double kMinStyleIntegral = 1e-3;
// Narrower Gaussians fall between the integration steps.
constexpr double kMinGaussSd = 1e-3;

// ---------------------------------------------------------------------------------------------
// The lexer: names, numbers, strings, the symbols { } ( ) = , and the end; `#` comments and all
// whitespace (newlines included) skipped.

enum class TokenKind { Name, Number, String, Symbol, End };

struct Token {
  TokenKind kind = TokenKind::End;
  std::string text;  // as written (a string without its quotes)
  double number = 0;
  FilePosition position;

  bool isSymbol(char c) const { return kind == TokenKind::Symbol && text[0] == c; }
  bool isWord(std::string_view word) const { return kind == TokenKind::Name && text == word; }
  // For "found ..." in messages.
  std::string describe() const {
    switch (kind) {
      case TokenKind::Name:
      case TokenKind::Symbol:
        return inQuotes(text);
      case TokenKind::Number:
        return text.size() > 40 ? text.substr(0, 40) + "..." : text;
      case TokenKind::String:
        return "string " + inQuotes(text, '"');
      case TokenKind::End:
        break;
    }
    return "the end of the file";
  }
};

class Lexer {
 public:
  Lexer(std::string_view text, const std::string& source) : text_(text), source_(source) {}

  const Token& peek() {
    if (!peeked_) peeked_ = scan();
    return *peeked_;
  }
  Token next() {
    Token token = peek();
    peeked_.reset();
    return token;
  }

  [[noreturn]] void fail(FilePosition at, const std::string& what) const {
    throwInputError(source_ + ":" + std::to_string(at.line) + ":" + std::to_string(at.column),
                    what);
  }

 private:
  bool more() const { return at_ < text_.size(); }
  char current() const { return more() ? text_[at_] : '\0'; }
  char ahead(std::size_t n) const { return at_ + n < text_.size() ? text_[at_ + n] : '\0'; }
  FilePosition here() const { return {line_, int(at_ - lineStart_) + 1}; }
  // A line ends at "\n", "\r\n" or a lone "\r" (old Mac files).
  bool endsLine() const { return current() == '\n' || (current() == '\r' && ahead(1) != '\n'); }
  void advance() {
    if (endsLine()) {
      ++line_;
      lineStart_ = at_ + 1;
    }
    ++at_;
  }
  static bool isDigit(char c) { return c >= '0' && c <= '9'; }
  static bool isNameStart(char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_';
  }

  void skipSpaceAndComments() {
    while (more()) {
      const char c = current();
      if (c == ' ' || c == '\t' || c == '\n' || c == '\r') {
        advance();
      } else if (c == '#') {
        while (more() && !endsLine()) advance();
      } else {
        return;
      }
    }
  }

  Token scan() {
    skipSpaceAndComments();
    Token token;
    token.position = here();
    if (!more()) return token;
    const char c = current();
    const std::size_t start = at_;
    if (isNameStart(c)) {
      while (more() && (isNameStart(current()) || isDigit(current()))) advance();
      token.kind = TokenKind::Name;
      token.text = std::string(text_.substr(start, at_ - start));
      return token;
    }
    const bool signedNumber =
        (c == '-' || c == '+') && (isDigit(ahead(1)) || (ahead(1) == '.' && isDigit(ahead(2))));
    if (isDigit(c) || (c == '.' && isDigit(ahead(1))) || signedNumber) return scanNumber(token);
    if (c == '"') return scanString(token);
    if (std::string_view("{}()=,").find(c) != std::string_view::npos) {
      advance();
      token.kind = TokenKind::Symbol;
      token.text = std::string(1, c);
      return token;
    }
    fail(token.position, "unexpected character " + inQuotes(std::string_view(&text_[at_], 1)));
  }

  // [+-] digits [. digits] [(e|E) [+-] digits], at least one digit before or after the point.
  Token scanNumber(Token& token) {
    const std::size_t start = at_;
    if (current() == '-' || current() == '+') advance();
    while (isDigit(current())) advance();
    if (current() == '.') {
      advance();
      while (isDigit(current())) advance();
    }
    if ((current() == 'e' || current() == 'E') &&
        (isDigit(ahead(1)) || ((ahead(1) == '-' || ahead(1) == '+') && isDigit(ahead(2))))) {
      advance();
      advance();
      while (isDigit(current())) advance();
    }
    token.kind = TokenKind::Number;
    token.text = std::string(text_.substr(start, at_ - start));
    const char* first = token.text.data() + (token.text[0] == '+' ? 1 : 0);
    const char* last = token.text.data() + token.text.size();
    const auto [end, ec] = std::from_chars(first, last, token.number);
    if (ec != std::errc() || end != last || !std::isfinite(token.number)) {
      fail(token.position, "number " + token.describe() + " is out of range (not a finite double)");
    }
    return token;
  }

  Token scanString(Token& token) {
    advance();  // the opening quote
    const std::size_t start = at_;
    while (more() && current() != '"') {
      const unsigned char c = static_cast<unsigned char>(current());
      if (c == '\n') break;
      if (c < 0x20 || c == 0x7f) {
        fail(here(),
             "unexpected character " + inQuotes(std::string_view(&text_[at_], 1)) + " in a string");
      }
      advance();
    }
    if (current() != '"') fail(token.position, "string not closed on its line");
    token.kind = TokenKind::String;
    token.text = std::string(text_.substr(start, at_ - start));
    advance();  // the closing quote
    if (token.text.size() > kMaxStringBytes) {
      fail(token.position, "string of " + std::to_string(token.text.size()) +
                               " bytes, more than the " + std::to_string(kMaxStringBytes) +
                               " allowed");
    }
    return token;
  }

  std::string_view text_;
  const std::string& source_;
  std::size_t at_ = 0;
  std::size_t lineStart_ = 0;
  int line_ = 1;
  std::optional<Token> peeked_;
};

// ---------------------------------------------------------------------------------------------
// The parser: recursive descent over
//
//   file       := { attribute | style | flatness | rule }
//   attribute  := 'attribute' NAME 'from' SOURCE '{' { value } '}'
//   style      := 'style' NAME [ 'priority' INTEGER ] '{' { 'spheres' '=' STRING | value } '}'
//   flatness   := 'flatness' '{' { value } '}'
//   value      := NAME '=' SHAPE '(' arguments ')'
//   rule       := 'rule' 'if' or 'then' (NAME | 'flatness') 'is' NAME
//   or         := and { 'or' and }
//   and        := unary { 'and' unary }
//   unary      := 'not' unary | '(' or ')' | NAME 'is' NAME
//
// Names in rules are resolved once the whole file is read, so blocks may follow the rules.

class Parser {
 public:
  Parser(std::string_view text, const std::string& source, const std::filesystem::path& baseDir)
      : lexer_(text, source), baseDir_(baseDir) {
    base_.source = source;
  }

  RuleBase parse() {
    while (lexer_.peek().kind != TokenKind::End) {
      const Token& token = lexer_.peek();
      if (token.isWord("attribute")) {
        parseAttribute();
      } else if (token.isWord("style")) {
        parseStyle();
      } else if (token.isWord("flatness")) {
        parseFlatness();
      } else if (token.isWord("rule")) {
        parseRule();
      } else {
        fail(token.position,
             "expected 'attribute', 'style', 'flatness' or 'rule', found " + token.describe());
      }
    }
    if (base_.styles.empty()) fail({1, 1}, "no style defined (a rule base needs at least one)");
    resolveRules();
    warnAboutUnused();
    return std::move(base_);
  }

 private:
  [[noreturn]] void fail(FilePosition at, const std::string& what) const { lexer_.fail(at, what); }
  void warn(FilePosition at, const std::string& what) {
    base_.warnings.push_back(base_.source + ":" + std::to_string(at.line) + ":" +
                             std::to_string(at.column) + ": warning: " + what);
  }

  // The next token must be the symbol `c`; `context` completes "expected 'c' ...".
  Token expectSymbol(char c, const std::string& context) {
    Token token = lexer_.next();
    if (!token.isSymbol(c)) {
      fail(token.position,
           "expected '" + std::string(1, c) + "' " + context + ", found " + token.describe());
    }
    return token;
  }
  Token expectWord(std::string_view word, const std::string& context) {
    Token token = lexer_.next();
    if (!token.isWord(word)) {
      fail(token.position,
           "expected '" + std::string(word) + "' " + context + ", found " + token.describe());
    }
    return token;
  }
  // A name that is not a word of the language; `what` says whose ("an attribute name").
  Token expectName(const std::string& what) {
    Token token = lexer_.next();
    if (token.kind != TokenKind::Name || isKeyword(token.text)) {
      fail(token.position, "expected " + what + ", found " + token.describe());
    }
    return token;
  }
  Token expectNumber(const std::string& what) {
    Token token = lexer_.next();
    if (token.kind != TokenKind::Number) {
      fail(token.position, "expected " + what + ", found " + token.describe());
    }
    return token;
  }

  // --- blocks -------------------------------------------------------------------------------

  void parseAttribute() {
    lexer_.next();  // attribute
    const Token name = expectName("an attribute name");
    if (const int first = base_.findAttribute(name.text); first >= 0) {
      fail(name.position, "attribute " + inQuotes(name.text) + " is defined twice (first at line " +
                              std::to_string(base_.attributes[first].position.line) + ")");
    }
    if (base_.attributes.size() == kMaxAttributes) {
      fail(name.position,
           "more than " + std::to_string(kMaxAttributes) + " attributes (the limit)");
    }
    Attribute attribute;
    attribute.name = name.text;
    attribute.position = name.position;
    expectWord("from", "after the attribute name");
    const Token source = lexer_.next();
    const auto known = std::find(kSourceNames.begin(), kSourceNames.end(), source.text);
    if (source.kind != TokenKind::Name || known == kSourceNames.end()) {
      fail(source.position,
           "unknown source " + source.describe() + " (known: " +
               joinNames(std::vector<std::string>(kSourceNames.begin(), kSourceNames.end())) + ")");
    }
    attribute.source = AttributeSource(known - kSourceNames.begin());
    expectSymbol('{', "to open the attribute's values");
    const std::string owner = "attribute " + inQuotes(attribute.name);
    while (!lexer_.peek().isSymbol('}')) {
      SemanticValue value = parseValue(owner, attribute.values);
      if (maximumOnUnit(value.function) <= 0.0) {
        fail(value.position, value.function.text() + " is zero everywhere on [0, 1]");
      }
      const std::vector<float> row = value.function.table(kMembershipTableSize);
      if (*std::max_element(row.begin(), row.end()) <= 0.0f) {
        fail(value.position, value.function.text() + " falls between the " +
                                 std::to_string(kMembershipTableSize) +
                                 " points where the renderer looks it up (x = k/" +
                                 std::to_string(kMembershipTableSize - 1) +
                                 "): make it wider, or put its peak on one of them");
      }
      attribute.values.push_back(std::move(value));
    }
    lexer_.next();  // }
    if (attribute.values.empty()) fail(name.position, owner + " has no values");
    base_.attributes.push_back(std::move(attribute));
  }

  void parseStyle() {
    lexer_.next();  // style
    const Token name = expectName("a style name");
    if (const int first = base_.findStyle(name.text); first >= 0) {
      fail(name.position, "style " + inQuotes(name.text) + " is defined twice (first at line " +
                              std::to_string(base_.styles[first].position.line) + ")");
    }
    if (base_.styles.size() == kMaxStyles) {
      fail(name.position, "more than " + std::to_string(kMaxStyles) + " styles (the limit)");
    }
    Style style;
    style.name = name.text;
    style.position = name.position;
    if (lexer_.peek().isWord("priority")) {
      lexer_.next();
      const Token priority = expectNumber("an integer priority");
      // Written as an integer: 1e2 and 100.0 are numbers of another kind.
      if (priority.text.find_first_of(".eE") != std::string::npos ||
          priority.number != std::floor(priority.number) || priority.number < 0 ||
          priority.number > 1000) {
        fail(priority.position,
             "priority must be an integer from 0 to 1000, found " + priority.describe());
      }
      style.priority = int(priority.number);
    }
    expectSymbol('{', "to open the style's entries");
    const std::string owner = "style " + inQuotes(style.name);
    std::optional<FilePosition> spheresAt;
    while (!lexer_.peek().isSymbol('}')) {
      if (lexer_.peek().isWord("spheres")) {
        const Token key = lexer_.next();
        if (spheresAt) {
          fail(key.position, "spheres given twice in " + owner + " (first at line " +
                                 std::to_string(spheresAt->line) + ")");
        }
        spheresAt = key.position;
        expectSymbol('=', "after 'spheres'");
        style.spheres = parseSpheres();
        continue;
      }
      style.values.push_back(parseStyleValue(owner, style.values));
    }
    lexer_.next();  // }
    if (!spheresAt) {
      fail(name.position, owner + " has no spheres = \"...\" (a built-in ramp or a .png file)");
    }
    if (style.values.empty()) fail(name.position, owner + " has no values");
    base_.styles.push_back(std::move(style));
  }

  void parseFlatness() {
    const Token keyword = lexer_.next();
    if (flatnessAt_) {
      fail(keyword.position,
           "flatness block given twice (first at line " + std::to_string(flatnessAt_->line) + ")");
    }
    flatnessAt_ = keyword.position;
    expectSymbol('{', "to open the flatness values");
    while (!lexer_.peek().isSymbol('}')) {
      base_.flatness.push_back(parseStyleValue("the flatness block", base_.flatness));
    }
    lexer_.next();  // }
    if (base_.flatness.empty()) fail(keyword.position, "the flatness block has no values");
  }

  Spheres parseSpheres() {
    const Token token = lexer_.next();
    if (token.kind != TokenKind::String) {
      fail(token.position,
           "expected a string (a built-in ramp or a .png file), found " + token.describe());
    }
    Spheres spheres;
    spheres.text = token.text;
    std::string lower = token.text;
    std::transform(lower.begin(), lower.end(), lower.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    if (lower.size() > 4 && lower.ends_with(".png")) {
      const std::filesystem::path file(token.text);
      spheres.file = file.is_absolute() || baseDir_.empty() ? file : baseDir_ / file;
      return spheres;
    }
    const auto& ramps = builtinSphereRamps();
    if (std::find(ramps.begin(), ramps.end(), token.text) == ramps.end()) {
      fail(token.position, "unknown sphere ramp " + inQuotes(token.text) +
                               " (built in: " + joinNames(ramps) + "; or a .png file)");
    }
    spheres.builtin = token.text;
    return spheres;
  }

  // A style's or the flatness' value: over [0, 1], integrated by the centroid.
  SemanticValue parseStyleValue(const std::string& owner, const std::vector<SemanticValue>& known) {
    SemanticValue value = parseValue(owner, known);
    const double integral = integralOnUnit(value.function);
    if (integral < kMinStyleIntegral) {
      fail(value.position, value.function.text() + " is (almost) zero on [0, 1]: its integral " +
                               formatNumber(integral) + " is below " +
                               formatNumber(kMinStyleIntegral) + " (the centroid divides by it)");
    }
    return value;
  }

  // NAME '=' SHAPE '(' ... ')'; `owner` names the block in messages ("style 'bone'").
  SemanticValue parseValue(const std::string& owner, const std::vector<SemanticValue>& known) {
    const Token name = expectName("a value name (name = shape(...)) or '}'");
    for (const auto& other : known) {
      if (other.name == name.text) {
        fail(name.position, "value " + inQuotes(name.text) + " is defined twice in " + owner +
                                " (first at line " + std::to_string(other.position.line) + ")");
      }
    }
    if (known.size() == kMaxValuesPerBlock) {
      fail(name.position, "more than " + std::to_string(kMaxValuesPerBlock) + " values in " +
                              owner + " (the limit)");
    }
    expectSymbol('=', "after the value name " + inQuotes(name.text));
    SemanticValue value;
    value.name = name.text;
    value.position = name.position;
    value.function = parseShape();
    return value;
  }

  MembershipFunction parseShape() {
    const Token name = lexer_.next();
    const auto known = std::find(kShapeNames.begin(), kShapeNames.end(), name.text);
    if (name.kind != TokenKind::Name || known == kShapeNames.end()) {
      fail(name.position,
           "unknown shape " + name.describe() + " (known: " +
               joinNames(std::vector<std::string>(kShapeNames.begin(), kShapeNames.end())) + ")");
    }
    MembershipFunction function;
    function.shape = Shape(known - kShapeNames.begin());
    expectSymbol('(', "after " + name.text);
    if (function.shape == Shape::Points) {
      parsePoints(name, function);
    } else {
      parseArguments(name, function);
    }
    return function;
  }

  void parseArguments(const Token& name, MembershipFunction& function) {
    while (!lexer_.peek().isSymbol(')')) {
      if (!function.parameters.empty()) expectSymbol(',', "between the numbers of " + name.text);
      function.parameters.push_back(expectNumber("a number").number);
    }
    expectSymbol(')', "to close " + name.text + "(");
    const std::vector<double>& p = function.parameters;
    const auto count = [&](std::size_t wanted, const char* names) {
      if (p.size() != wanted) {
        fail(name.position, name.text + " takes " + std::to_string(wanted) + " numbers (" + names +
                                "), found " + std::to_string(p.size()));
      }
    };
    switch (function.shape) {
      case Shape::Trapezoid:
        count(4, "a, b, c, d");
        if (!(p[0] <= p[1] && p[1] <= p[2] && p[2] <= p[3])) {
          fail(name.position, function.text() + " is inverted: needs a <= b <= c <= d");
        }
        break;
      case Shape::Triangle:
        count(3, "a, b, c");
        if (!(p[0] <= p[1] && p[1] <= p[2])) {
          fail(name.position, function.text() + " is inverted: needs a <= b <= c");
        }
        break;
      case Shape::Gauss:
        count(2, "mean, sd");
        if (!(p[1] >= kMinGaussSd)) {
          fail(name.position, function.text() + " needs sd >= " + formatNumber(kMinGaussSd));
        }
        break;
      case Shape::Points:
        break;
    }
  }

  void parsePoints(const Token& name, MembershipFunction& function) {
    while (true) {
      const Token open = expectSymbol('(', "to open a point (x, y)");
      const double x = expectNumber("the x of a point").number;
      expectSymbol(',', "between a point's x and y");
      const Token y = expectNumber("the y of a point");
      expectSymbol(')', "to close a point (x, y)");
      const std::string which = "point " + std::to_string(function.points.size() + 1);
      if (!function.points.empty() && !(x > function.points.back().x)) {
        fail(open.position, "points: x must increase, but " + which + " has x " + formatNumber(x) +
                                " after " + formatNumber(function.points.back().x));
      }
      if (!(y.number >= 0.0 && y.number <= 1.0)) {
        fail(y.position, "points: y of " + which + " must be in [0, 1], found " + y.describe());
      }
      if (function.points.size() == kMaxShapePoints) {
        fail(open.position, "points takes at most " + std::to_string(kMaxShapePoints) + " points");
      }
      function.points.emplace_back(x, y.number);
      if (!lexer_.peek().isSymbol(',')) break;
      lexer_.next();
    }
    expectSymbol(')', "to close points(");
    if (function.points.size() < 2) {
      fail(name.position, "points takes 2 to " + std::to_string(kMaxShapePoints) +
                              " points (x, y), found " + std::to_string(function.points.size()));
    }
  }

  // --- rules --------------------------------------------------------------------------------

  void parseRule() {
    Rule rule;
    rule.position = lexer_.next().position;  // rule
    if (base_.rules.size() == kMaxRules) {
      fail(rule.position, "more than " + std::to_string(kMaxRules) + " rules (the limit)");
    }
    expectWord("if", "after 'rule'");
    std::size_t terms = 0;
    rule.antecedent = parseOr(0, terms);
    expectWord("then", "after the condition");
    const Token target = lexer_.next();
    if (target.kind != TokenKind::Name || (isKeyword(target.text) && target.text != "flatness")) {
      fail(target.position, "expected a style name or 'flatness', found " + target.describe());
    }
    rule.target = target.text;
    rule.targetPosition = target.position;
    rule.flatness = target.text == "flatness";
    expectWord("is", "after " + inQuotes(target.text));
    const Token value = expectName("a value name");
    rule.valueName = value.text;
    rule.valuePosition = value.position;
    base_.rules.push_back(std::move(rule));
  }

  Condition parseOr(int depth, std::size_t& terms) {
    Condition first = parseAnd(depth, terms);
    if (!lexer_.peek().isWord("or")) return first;
    Condition node;
    node.op = Condition::Op::Or;
    node.position = first.position;
    node.operands.push_back(std::move(first));
    while (lexer_.peek().isWord("or")) {
      lexer_.next();
      node.operands.push_back(parseAnd(depth, terms));
    }
    return node;
  }

  Condition parseAnd(int depth, std::size_t& terms) {
    Condition first = parseUnary(depth, terms);
    if (!lexer_.peek().isWord("and")) return first;
    Condition node;
    node.op = Condition::Op::And;
    node.position = first.position;
    node.operands.push_back(std::move(first));
    while (lexer_.peek().isWord("and")) {
      lexer_.next();
      node.operands.push_back(parseUnary(depth, terms));
    }
    return node;
  }

  Condition parseUnary(int depth, std::size_t& terms) {
    const Token token = lexer_.next();
    if (token.isWord("not") || token.isSymbol('(')) {
      if (depth == kMaxConditionDepth) {
        fail(token.position, "condition nested deeper than " + std::to_string(kMaxConditionDepth) +
                                 " (not and parentheses; the limit)");
      }
      if (token.isSymbol('(')) {
        Condition inner = parseOr(depth + 1, terms);
        expectSymbol(')', "to close the '(' at line " + std::to_string(token.position.line) +
                              ", column " + std::to_string(token.position.column));
        return inner;
      }
      Condition node;
      node.op = Condition::Op::Not;
      node.position = token.position;
      node.operands.push_back(parseUnary(depth + 1, terms));
      return node;
    }
    if (token.kind != TokenKind::Name || isKeyword(token.text)) {
      fail(token.position,
           "expected an attribute name, 'not' or '(' in the condition, found " + token.describe());
    }
    if (++terms > kMaxTermsPerRule) {
      fail(token.position,
           "rule has more than " + std::to_string(kMaxTermsPerRule) + " terms (the limit)");
    }
    Condition term;
    term.attributeName = token.text;
    term.position = token.position;
    expectWord("is", "after the attribute name " + inQuotes(token.text));
    const Token value = expectName("a value name");
    term.valueName = value.text;
    term.valuePosition = value.position;
    return term;
  }

  // --- names --------------------------------------------------------------------------------

  void resolveCondition(Condition& condition) {
    for (auto& operand : condition.operands) resolveCondition(operand);
    if (condition.op != Condition::Op::Is) return;
    condition.attribute = base_.findAttribute(condition.attributeName);
    if (condition.attribute < 0) {
      fail(condition.position, "unknown attribute " + inQuotes(condition.attributeName) +
                                   " (known: " + joinItemNames(base_.attributes) + ")");
    }
    const Attribute& attribute = base_.attributes[condition.attribute];
    condition.value = findValue(attribute.values, condition.valueName);
    if (condition.value < 0) {
      fail(condition.valuePosition, "attribute " + inQuotes(attribute.name) + " has no value " +
                                        inQuotes(condition.valueName) + " (it has " +
                                        joinItemNames(attribute.values) + ")");
    }
    attributeUsed_[condition.attribute] = true;
  }

  void resolveRules() {
    attributeUsed_.assign(base_.attributes.size(), false);
    styleReached_.assign(base_.styles.size(), false);
    for (Rule& rule : base_.rules) {
      resolveCondition(rule.antecedent);
      const std::vector<SemanticValue>* values = &base_.flatness;
      std::string owner = "the flatness block";
      if (rule.flatness) {
        if (base_.flatness.empty()) {
          fail(rule.targetPosition, "no flatness block defines the flatness values");
        }
        flatnessReached_ = true;
      } else {
        rule.style = base_.findStyle(rule.target);
        if (rule.style < 0) {
          std::vector<std::string> names;
          for (const auto& style : base_.styles) names.push_back(style.name);
          if (!base_.flatness.empty()) names.push_back("flatness");
          fail(rule.targetPosition,
               "unknown style " + inQuotes(rule.target) + " (known: " + joinNames(names) + ")");
        }
        values = &base_.styles[rule.style].values;
        owner = "style " + inQuotes(rule.target);
        styleReached_[rule.style] = true;
      }
      rule.value = findValue(*values, rule.valueName);
      if (rule.value < 0) {
        fail(rule.valuePosition, owner + " has no value " + inQuotes(rule.valueName) + " (it has " +
                                     joinItemNames(*values) + ")");
      }
    }
  }

  void warnAboutUnused() {
    // In file order: attributes, styles and the flatness block interleave.
    struct Unused {
      FilePosition position;
      std::string what;
    };
    std::vector<Unused> unused;
    for (std::size_t i = 0; i < base_.attributes.size(); ++i) {
      if (!attributeUsed_[i]) {
        unused.push_back(
            {base_.attributes[i].position,
             "attribute " + inQuotes(base_.attributes[i].name) + " is used by no rule"});
      }
    }
    for (std::size_t i = 0; i < base_.styles.size(); ++i) {
      if (!styleReached_[i]) {
        unused.push_back({base_.styles[i].position, "style " + inQuotes(base_.styles[i].name) +
                                                        " is reached by no rule (never drawn)"});
      }
    }
    if (flatnessAt_ && !flatnessReached_) {
      unused.push_back(
          {*flatnessAt_, "the flatness block is reached by no rule (flatness stays 0)"});
    }
    std::stable_sort(unused.begin(), unused.end(), [](const Unused& a, const Unused& b) {
      return std::tie(a.position.line, a.position.column) <
             std::tie(b.position.line, b.position.column);
    });
    for (const auto& item : unused) warn(item.position, item.what);
  }

  static int findValue(const std::vector<SemanticValue>& values, std::string_view name) {
    for (std::size_t i = 0; i < values.size(); ++i) {
      if (values[i].name == name) return int(i);
    }
    return -1;
  }

  Lexer lexer_;
  std::filesystem::path baseDir_;
  RuleBase base_;
  std::optional<FilePosition> flatnessAt_;
  bool flatnessReached_ = false;
  std::vector<bool> attributeUsed_, styleReached_;
};

}  // namespace

// -----------------------------------------------------------------------------------------------

const char* attributeSourceName(AttributeSource source) {
  return kSourceNames[int(source)];
}

const char* shapeName(Shape shape) {
  return kShapeNames[int(shape)];
}

double MembershipFunction::at(double x) const {
  if (std::isnan(x)) return 0.0;
  double degree = 0.0;
  switch (shape) {
    case Shape::Trapezoid:
      degree = trapezoidAt(x, parameters[0], parameters[1], parameters[2], parameters[3]);
      break;
    case Shape::Triangle:
      degree = trapezoidAt(x, parameters[0], parameters[1], parameters[1], parameters[2]);
      break;
    case Shape::Gauss: {
      const double z = (x - parameters[0]) / parameters[1];
      degree = std::exp(-0.5 * z * z);
      break;
    }
    case Shape::Points:
      degree = pointsAt(x, points);
      break;
  }
  return std::isnan(degree) ? 0.0 : std::clamp(degree, 0.0, 1.0);
}

std::vector<float> MembershipFunction::table(int size) const {
  std::vector<float> entries(std::size_t(std::max(size, 2)));
  for (std::size_t k = 0; k < entries.size(); ++k) {
    entries[k] = float(at(double(k) / double(entries.size() - 1)));
  }
  return entries;
}

std::string MembershipFunction::text() const {
  std::string out = std::string(shapeName(shape)) + "(";
  if (shape == Shape::Points) {
    for (std::size_t i = 0; i < points.size(); ++i) {
      out += (i ? ", (" : "(") + formatNumber(points[i].x) + ", " + formatNumber(points[i].y) + ")";
    }
  } else {
    for (std::size_t i = 0; i < parameters.size(); ++i) {
      out += (i ? ", " : "") + formatNumber(parameters[i]);
    }
  }
  return out + ")";
}

const std::vector<std::string>& builtinSphereRamps() {
  static const std::vector<std::string> ramps = {"gray", "ivory", "skin", "red", "green", "blue"};
  return ramps;
}

int RuleBase::findAttribute(std::string_view name) const {
  for (std::size_t i = 0; i < attributes.size(); ++i) {
    if (attributes[i].name == name) return int(i);
  }
  return -1;
}

int RuleBase::findStyle(std::string_view name) const {
  for (std::size_t i = 0; i < styles.size(); ++i) {
    if (styles[i].name == name) return int(i);
  }
  return -1;
}

std::array<bool, kAttributeSourceCount> RuleBase::usedSources() const {
  std::array<bool, kAttributeSourceCount> used{};
  const auto visit = [&](const auto& self, const Condition& condition) -> void {
    if (condition.op == Condition::Op::Is) {
      used[int(attributes[condition.attribute].source)] = true;
    }
    for (const auto& operand : condition.operands) self(self, operand);
  };
  for (const Rule& rule : rules) visit(visit, rule.antecedent);
  return used;
}

RuleBase parseRulesText(std::string_view text, const std::string& source,
                        const std::filesystem::path& baseDir) {
  if (text.size() > limits::kMaxHeaderBytes) {
    throwInputError(source, "rule text of " + std::to_string(text.size()) +
                                " bytes, more than the " + std::to_string(limits::kMaxHeaderBytes) +
                                " allowed");
  }
  // A UTF-8 byte-order mark (what some Windows editors put first) is no rule text: skipped, as
  // the JSON inputs skip it. Positions in messages count from after it.
  if (text.starts_with("\xEF\xBB\xBF")) text.remove_prefix(3);
  return Parser(text, source, baseDir).parse();
}

RuleBase loadRules(const std::string& path) {
  const std::string text = io::readWholeFile(path, limits::kMaxHeaderBytes);
  return parseRulesText(text, path, std::filesystem::path(path).parent_path());
}

std::vector<std::string> rulePresetNames() {
  std::vector<std::string> names;
  for (std::string_view path : embeddedRulePaths()) {
    if (path.ends_with(".rules")) names.emplace_back(path.substr(0, path.size() - 6));
  }
  std::sort(names.begin(), names.end());
  return names;
}

bool isRulesFile(std::string_view text) {
  return text.ends_with(".rules") || text.find('/') != std::string_view::npos;
}

RuleBase loadRulesPreset(const std::string& nameOrFile, const std::string& where) {
  // Rule text itself (it holds an attribute block's '{'); a spheres PNG it names is read from
  // the working directory.
  if (isInlineSource(nameOrFile)) return parseRulesText(nameOrFile, where, {});
  if (isRulesFile(nameOrFile)) return loadRules(nameOrFile);
  const auto names = rulePresetNames();
  if (std::find(names.begin(), names.end(), nameOrFile) == names.end()) {
    std::string known;
    for (const auto& name : names) known += (known.empty() ? "" : ", ") + name;
    if (nameOrFile.find_first_not_of(" \t\r\n") == std::string::npos) {
      throwInputError(where, "is empty: give a preset (" + known + ") or a .rules file");
    }
    throwInputError(
        where, "unknown preset '" + nameOrFile + "' (presets: " + known + "; or a .rules file)");
  }
  // Presets name only built-in sphere ramps: there is no folder beside them.
  return parseRulesText(embeddedRuleSource(nameOrFile + ".rules"), nameOrFile + ".rules", {});
}

// -----------------------------------------------------------------------------------------------
// Defuzzification tables.

int DefuzzTables::row(const Rule& rule) const {
  return (rule.flatness ? firstRow.back() : firstRow[std::size_t(rule.style)]) + rule.value;
}

namespace {

double interpolateRow(const std::vector<float>& table, int size, int row, double degree) {
  const double t = std::clamp(degree, 0.0, 1.0) * double(size - 1);
  const int k = std::min(int(t), size - 2);
  const double f = t - double(k);
  const float* entries = table.data() + std::size_t(row) * std::size_t(size);
  return double(entries[k]) * (1.0 - f) + double(entries[k + 1]) * f;
}

// N(d) = ∫ x·min(m(x), d) dx and D(d) = ∫ min(m(x), d) dx for every table degree, from the
// midpoint samples of m sorted by value: with j samples below d, D(d) = Σ_{below} m + d·(M − j)
// and N(d) = Σ_{below} x·m + d·Σ_{rest} x.
void tabulate(const MembershipFunction& function, int size, float* numerator, float* denominator) {
  struct Sample {
    double m, x;
  };
  std::vector<Sample> samples(kIntegrationSteps);
  for (int i = 0; i < kIntegrationSteps; ++i) {
    const double x = (i + 0.5) / kIntegrationSteps;
    samples[std::size_t(i)] = {function.at(x), x};
  }
  std::sort(samples.begin(), samples.end(),
            [](const Sample& a, const Sample& b) { return a.m < b.m; });
  // below[j]: sums over the j smallest samples; restX[j]: Σ x over the others.
  std::vector<double> belowM(samples.size() + 1, 0.0), belowXM(samples.size() + 1, 0.0),
      restX(samples.size() + 1, 0.0);
  for (std::size_t j = 0; j < samples.size(); ++j) {
    belowM[j + 1] = belowM[j] + samples[j].m;
    belowXM[j + 1] = belowXM[j] + samples[j].x * samples[j].m;
  }
  for (std::size_t j = samples.size(); j-- > 0;) restX[j] = restX[j + 1] + samples[j].x;
  const double dx = 1.0 / kIntegrationSteps;
  for (int k = 0; k < size; ++k) {
    const double d = double(k) / double(size - 1);
    const std::size_t j =
        std::size_t(std::lower_bound(samples.begin(), samples.end(), d,
                                     [](const Sample& s, double v) { return s.m < v; }) -
                    samples.begin());
    denominator[k] = float((belowM[j] + d * double(samples.size() - j)) * dx);
    numerator[k] = float((belowXM[j] + d * restX[j]) * dx);
  }
}

}  // namespace

double DefuzzTables::numeratorAt(int row, double degree) const {
  return interpolateRow(numerator, size, row, degree);
}

double DefuzzTables::denominatorAt(int row, double degree) const {
  return interpolateRow(denominator, size, row, degree);
}

DefuzzTables buildDefuzzTables(const RuleBase& rules, int size) {
  DefuzzTables tables;
  tables.size = std::max(size, 2);
  std::vector<const MembershipFunction*> functions;
  for (const Style& style : rules.styles) {
    tables.firstRow.push_back(int(functions.size()));
    for (const auto& value : style.values) functions.push_back(&value.function);
  }
  tables.firstRow.push_back(int(functions.size()));
  for (const auto& value : rules.flatness) functions.push_back(&value.function);
  tables.rows = int(functions.size());
  const std::size_t entries = std::size_t(tables.rows) * std::size_t(tables.size);
  tables.numerator.assign(entries, 0.0f);
  tables.denominator.assign(entries, 0.0f);
  for (std::size_t r = 0; r < functions.size(); ++r) {
    const std::size_t offset = r * std::size_t(tables.size);
    tabulate(*functions[r], tables.size, tables.numerator.data() + offset,
             tables.denominator.data() + offset);
  }
  return tables;
}

double tableCentroid(const DefuzzTables& tables, std::span<const RuleActivation> activations) {
  double numerator = 0.0, denominator = 0.0;
  for (const RuleActivation& a : activations) {
    numerator += tables.numeratorAt(a.row, a.degree);
    denominator += tables.denominatorAt(a.row, a.degree);
  }
  return denominator > 0.0 ? numerator / denominator : 0.0;
}

}  // namespace vsil
