#pragma once
// Fuzzy rule bases (Rautek, Bruckner & Gröller, EuroVis 2008), the CPU side of technique
// `semantic`: the `.rules` file format, membership functions, and the paper's precomputed
// defuzzification tables. No GL here; the rule compiler and the slice shaders belong in
// slicing/techniques/semantic/ (not written yet), the CPU reference of the whole fuzzy pipeline
// (direct centroid integration) in tests/reference/semantic_reference.h. The parser is a fuzz
// target (tests/fuzz/fuzz_rules.cpp). Examples: src/core/rules/*.rules.
//
// The format, by example:
//
//   # comment to the end of the line
//   attribute density from data {             # a named input, normalized to [0, 1]
//     low  = trapezoid(0.00, 0.00, 0.15, 0.30) # its semantic values: membership functions
//     high = trapezoid(0.25, 0.45, 1.00, 1.00)
//   }
//   attribute focus from cursor_distance { near = trapezoid(0, 0, 0.05, 0.15) }
//   style bone priority 2 {                   # a style: a lit-sphere ramp over [0, 1]
//     spheres = "ivory"                       #   a built-in ramp or a .png strip of spheres
//     transparent = trapezoid(0, 0, 0.1, 0.3) #   semantic values of the ramp parameter
//     opaque      = trapezoid(0.6, 0.9, 1, 1)
//   }
//   flatness { low = trapezoid(0, 0, 0.1, 0.3)  high = trapezoid(0.6, 0.9, 1, 1) }
//   rule if density is high and not (focus is near) then bone is opaque
//   rule if focus is near then flatness is high
//
// Newlines are whitespace like any other: a block may sit on one line with its entries separated
// by spaces. Names are [A-Za-z_][A-Za-z0-9_]*; the words of the language (attribute, from, style,
// priority, flatness, spheres, rule, if, then, is, and, or, not) are not names. `priority` (an
// integer, default 0) orders styles when they are composited (higher on top; equal priorities by
// the order of declaration, later on top). Attributes, styles and their values are referred to by
// name; attributes and styles have separate name spaces.
//
// Shapes (x in the attribute's normalized [0, 1], or the style parameter's [0, 1]):
//   trapezoid(a, b, c, d)  a <= b <= c <= d: 0 outside (a, d), rising on [a, b], 1 on [b, c],
//                          falling on [c, d]; a == b (c == d) is a vertical edge, 1 at the edge
//   triangle(a, b, c)      trapezoid(a, b, b, c)
//   gauss(mean, sd)        exp(-(x - mean)² / (2 sd²)), sd > 0
//   points((x, y), ...)    2 to 64 points, x strictly increasing, y in [0, 1]; linear between
//                          them, constant beyond the first and the last
// An attribute's value must not be zero everywhere on [0, 1] (the term could never hold); a
// style's or the flatness' value needs an integral of at least 0.001 on [0, 1] (the centroid
// divides by it), and a Gaussian an sd of at least 0.001 (the integration's resolution).
//
// Antecedents: `and` = min, `or` = max, `not` = 1 − x, parentheses; `not` binds tightest, then
// `and`, then `or`. Implication truncates the consequent's membership function at the
// antecedent's degree, aggregation sums, defuzzification takes the centroid (see DefuzzTables).
//
// Errors: InputError "FILE:LINE:COLUMN: what" (line and column from 1; columns count bytes), one
// line, e.g. "bone.rules:3:31: trapezoid takes 4 numbers (a, b, c, d), found 3". What a user
// may have meant but is not wrong (a style or the flatness block that no rule reaches, an
// attribute no rule uses) is a warning in RuleBase::warnings, in the same form.
#include <array>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

namespace vsil {

// Where an attribute's value comes from; each normalized to [0, 1]: data by the volume's value
// range, gradient magnitude by its maximum, distances by the volume box's diagonal (voxels scaled
// by the spacing), image_distance by the image diagonal, view_angle as the angle between gradient
// and view over 180°, time as given.
enum class AttributeSource {
  Data,
  Gradient,
  CursorDistance,
  PlaneDistance,
  ImageDistance,
  ViewAngle,
  Time
};
inline constexpr int kAttributeSourceCount = 7;
// "data", "gradient", "cursor_distance", ... as in the file.
const char* attributeSourceName(AttributeSource source);

// The normalized value of every source at one sample, indexed by int(AttributeSource).
using AttributeInputs = std::array<double, kAttributeSourceCount>;

enum class Shape { Trapezoid, Triangle, Gauss, Points };
const char* shapeName(Shape shape);

// Entries per membership-function row the renderer looks terms up in: entry k at x = k / (size
// − 1). 1024 keeps the linear interpolation within slope/4096 of a piecewise-linear function (a
// trapezoid's edge 0.1 wide: 0.6/255) and of a Gaussian (sd 0.05) within 1e-4. An attribute
// value zero at every entry never holds there, and is refused.
inline constexpr int kMembershipTableSize = 1024;

struct MembershipFunction {
  Shape shape = Shape::Trapezoid;
  std::vector<double> parameters;  // trapezoid a, b, c, d; triangle a, b, c; gauss mean, sd
  std::vector<glm::dvec2> points;  // points (x, y)

  // The degree of membership of x, in [0, 1].
  double at(double x) const;
  // `size` (>= 2) samples, entry k at x = k / (size − 1): a 1D texture row.
  std::vector<float> table(int size) const;
  // As written in a file: "trapezoid(0, 0, 0.1, 0.3)".
  std::string text() const;
};

// Where something was written in the file (from 1).
struct FilePosition {
  int line = 0;
  int column = 0;
};

struct SemanticValue {
  std::string name;
  MembershipFunction function;
  FilePosition position;
};

struct Attribute {
  std::string name;
  AttributeSource source = AttributeSource::Data;
  std::vector<SemanticValue> values;  // at least one
  FilePosition position;
};

// The lit-sphere ramp of a style: a built-in one by name, or a PNG strip of spheres.
struct Spheres {
  std::string text;            // as written between the quotes
  std::string builtin;         // one of builtinSphereRamps(), or empty
  std::filesystem::path file;  // a .png, relative paths resolved against the rule file's folder
};
// The built-in ramps: gray, ivory, skin, red, green, blue.
const std::vector<std::string>& builtinSphereRamps();

struct Style {
  std::string name;
  int priority = 0;
  Spheres spheres;
  std::vector<SemanticValue> values;  // at least one, over the ramp parameter in [0, 1]
  FilePosition position;
};

// An antecedent: a tree of `attribute is value` terms under and/or/not. And and Or hold two or
// more operands (a chain "a and b and c" is one node), Not one.
struct Condition {
  enum class Op { Is, Not, And, Or };
  Op op = Op::Is;
  int attribute = -1;  // Is: index into RuleBase::attributes
  int value = -1;      // Is: index into that attribute's values
  std::vector<Condition> operands;
  std::string attributeName, valueName;  // Is: as written
  FilePosition position;       // of the term (Is), the operator (Not) or the first operand
  FilePosition valuePosition;  // Is: of the value's name
};

// `rule if <antecedent> then <consequent> is <value>`.
struct Rule {
  Condition antecedent;
  bool flatness = false;          // the consequent is the flatness, not a style
  int style = -1;                 // index into RuleBase::styles when !flatness
  int value = -1;                 // index into the style's (or the flatness') values
  std::string target, valueName;  // the consequent as written ("bone", "opaque"; "flatness")
  FilePosition position;          // of `rule`
  FilePosition targetPosition, valuePosition;
};

// Size limits, checked while parsing (the file itself: at most limits::kMaxHeaderBytes, 1 MiB).
inline constexpr std::size_t kMaxRules = 256;
inline constexpr std::size_t kMaxAttributes = 32;
inline constexpr std::size_t kMaxStyles = 32;
inline constexpr std::size_t kMaxValuesPerBlock = 32;  // values of an attribute, style, flatness
inline constexpr std::size_t kMaxShapePoints = 64;
inline constexpr int kMaxConditionDepth = 32;        // nested not / parentheses
inline constexpr std::size_t kMaxTermsPerRule = 64;  // `attribute is value` terms
inline constexpr std::size_t kMaxStringBytes = 1024;

struct RuleBase {
  std::string source;  // the file name used in messages
  std::vector<Attribute> attributes;
  std::vector<Style> styles;
  std::vector<SemanticValue> flatness;  // empty: no flatness block
  std::vector<Rule> rules;
  std::vector<std::string> warnings;  // "FILE:L:C: warning: ...", in file order

  // Indexes, or -1.
  int findAttribute(std::string_view name) const;
  int findStyle(std::string_view name) const;
  // The sources the rules read (the shader computes only these), by int(AttributeSource).
  std::array<bool, kAttributeSourceCount> usedSources() const;
};

// Parses rule text; `source` names it in messages, `baseDir` resolves relative sphere files.
RuleBase parseRulesText(std::string_view text, const std::string& source,
                        const std::filesystem::path& baseDir = {});
// Reads (at most 1 MiB) and parses a file.
RuleBase loadRules(const std::string& path);

// The rule bases shipped with vsil (src/core/rules/*.rules, embedded), by name without ".rules":
// default, example, fig6-cube, tooth-focus-context.
std::vector<std::string> rulePresetNames();
// A text ending in ".rules" or holding a '/' is a file; anything else names a preset (messages
// then name "NAME.rules"); InputError "WHERE: unknown preset ..." for other names, `where`
// naming what gave it (the --rules flag, or the rules command's FILE).
bool isRulesFile(std::string_view text);
RuleBase loadRulesPreset(const std::string& nameOrFile, const std::string& where = "--rules");

// The paper's defuzzification (its equations 2-6): for a consequent (a style or the flatness)
// with semantic values m_j, a rule i of degree a_i adds min(m_j(x), a_i) to the aggregated
// function f, whose centroid is
//
//   c = Σ_i N_j(i)(a_i) / Σ_i D_j(i)(a_i),  N_j(a) = ∫₀¹ x·min(m_j(x), a) dx,  D_j(a) = ∫₀¹
//   min(m_j(x), a) dx.
//
// N_j and D_j are tabulated over the degree; the shader does two lookups per rule, sums and one
// division. A consequent no rule fires at a sample (every a_i = 0) has no centroid: its weight
// (the largest a_i, see tests/reference/semantic_reference.h) is 0 and it contributes nothing.
//
// Accuracy (tests/core/semantic_defuzz_test.cpp): with 256 entries the table centroid is within
// 1/255 of the directly integrated one wherever the consequent's weight is at least 2/255. Below
// that the tables cannot resolve the degree: between degree 0 and the first entry interpolation
// scales N and D alike, so a lone rule gets its value's centroid truncated at 1/255, which for a
// Gaussian's tails can be far (measured up to 83/255) from the centroid at its own tiny degree.
struct DefuzzTables {
  int size = 0;                  // entries per row; entry k at degree k / (size − 1)
  int rows = 0;                  // one per semantic value: the styles' in order, then the flatness'
  std::vector<float> numerator;  // rows × size, row after row (an R32F size × rows texture)
  std::vector<float> denominator;  // the same layout
  std::vector<int> firstRow;       // per style, then one for the flatness: its value 0's row

  int row(const Rule& rule) const;
  // Linear interpolation between the entries around `degree` (clamped to [0, 1]), as the shader
  // does it: two texelFetch and a mix, not GL_LINEAR, whose 8-bit filter weights would cost
  // precision.
  double numeratorAt(int row, double degree) const;
  double denominatorAt(int row, double degree) const;
};
inline constexpr int kDefaultDefuzzTableSize = 256;

// Tables of every style's and the flatness' values (size >= 2), integrated numerically.
DefuzzTables buildDefuzzTables(const RuleBase& rules, int size = kDefaultDefuzzTableSize);

// What the shader computes for one consequent from its rules' (row, degree) pairs: the centroid
// Σ N / Σ D, or 0 where Σ D is 0 (no rule fires).
struct RuleActivation {
  int row = 0;
  double degree = 0;
};
double tableCentroid(const DefuzzTables& tables, std::span<const RuleActivation> activations);

}  // namespace vsil
