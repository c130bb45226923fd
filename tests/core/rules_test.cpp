// Rule bases (core/rules.h): the issue's example parsed to the structure it spells out, the shapes
// at hand-computed points, every class of bad input with the exact one-line message it gives
// (file, line and column included), warnings, the shipped example files, and the
// defuzzification tables against integrals computed by hand.
#include <cmath>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "core/error.h"
#include "core/limits.h"
#include "core/rules.h"
#include "io/file_access.h"

namespace vsil {
namespace {

const std::filesystem::path kRulesDir = std::filesystem::path(VSIL_SOURCE_DIR) / "src/core/rules";

// The message of the InputError parsing `text` throws ("" if it parses).
std::string parseError(const std::string& text) {
  try {
    parseRulesText(text, "t.rules");
  } catch (const InputError& error) {
    return error.what();
  }
  return "";
}

MembershipFunction shapeOf(const std::string& text) {
  const RuleBase base = parseRulesText("style s { spheres = \"gray\"  v = " + text + " }", "t");
  return base.styles.at(0).values.at(0).function;
}

TEST(Rules, TheIssuesExampleParsesToItsStructure) {
  const RuleBase base = loadRules((kRulesDir / "example.rules").string());
  ASSERT_EQ(base.attributes.size(), 2u);
  const Attribute& density = base.attributes[0];
  EXPECT_EQ(density.name, "density");
  EXPECT_EQ(density.source, AttributeSource::Data);
  ASSERT_EQ(density.values.size(), 2u);
  EXPECT_EQ(density.values[0].name, "low");
  EXPECT_EQ(density.values[0].function.shape, Shape::Trapezoid);
  EXPECT_EQ(density.values[0].function.parameters, (std::vector<double>{0.0, 0.0, 0.15, 0.30}));
  EXPECT_EQ(density.values[1].function.text(), "trapezoid(0.25, 0.45, 1, 1)");
  EXPECT_EQ(density.position.line, 3);
  EXPECT_EQ(density.position.column, 11);
  EXPECT_EQ(base.attributes[1].name, "focus");
  EXPECT_EQ(base.attributes[1].source, AttributeSource::CursorDistance);

  ASSERT_EQ(base.styles.size(), 2u);
  const Style& bone = base.styles[0];
  EXPECT_EQ(bone.name, "bone");
  EXPECT_EQ(bone.priority, 2);
  EXPECT_EQ(bone.spheres.builtin, "ivory");
  EXPECT_TRUE(bone.spheres.file.empty());
  ASSERT_EQ(bone.values.size(), 2u);
  EXPECT_EQ(bone.values[1].name, "opaque");
  // The one-line style: entries separated by spaces only.
  const Style& skin = base.styles[1];
  EXPECT_EQ(skin.name, "skin");
  EXPECT_EQ(skin.priority, 1);
  EXPECT_EQ(skin.spheres.builtin, "skin");
  ASSERT_EQ(skin.values.size(), 2u);
  EXPECT_EQ(skin.values[0].function.text(), "triangle(0, 0, 0.3)");
  EXPECT_EQ(skin.values[1].function.text(), "trapezoid(0.5, 0.8, 1, 1)");
  ASSERT_EQ(base.flatness.size(), 2u);
  EXPECT_EQ(base.flatness[1].name, "high");

  ASSERT_EQ(base.rules.size(), 4u);
  const Rule& first = base.rules[0];
  EXPECT_EQ(first.antecedent.op, Condition::Op::Is);
  EXPECT_EQ(first.antecedent.attribute, 0);
  EXPECT_EQ(first.antecedent.value, 1);
  EXPECT_FALSE(first.flatness);
  EXPECT_EQ(first.style, 0);
  EXPECT_EQ(first.value, 1);
  // "density is low and not focus is near": and(is, not(is)).
  const Condition& second = base.rules[1].antecedent;
  ASSERT_EQ(second.op, Condition::Op::And);
  ASSERT_EQ(second.operands.size(), 2u);
  EXPECT_EQ(second.operands[0].op, Condition::Op::Is);
  EXPECT_EQ(second.operands[0].value, 0);
  ASSERT_EQ(second.operands[1].op, Condition::Op::Not);
  EXPECT_EQ(second.operands[1].operands.at(0).attribute, 1);
  EXPECT_EQ(base.rules[1].style, 1);
  EXPECT_EQ(base.rules[1].value, 1);
  EXPECT_EQ(base.rules[2].value, 0);
  EXPECT_TRUE(base.rules[3].flatness);
  EXPECT_EQ(base.rules[3].value, 1);
  EXPECT_EQ(base.rules[3].position.line, 20);
  EXPECT_TRUE(base.warnings.empty()) << base.warnings.front();

  const auto used = base.usedSources();
  EXPECT_TRUE(used[int(AttributeSource::Data)]);
  EXPECT_TRUE(used[int(AttributeSource::CursorDistance)]);
  EXPECT_FALSE(used[int(AttributeSource::Gradient)]);
}

TEST(Rules, PrecedenceIsNotThenAndThenOrAndChainsAreOneNode) {
  const RuleBase base = parseRulesText(
      "attribute a from data { x = triangle(0, 0.5, 1)  y = gauss(0.5, 0.1) }\n"
      "attribute t from time { z = trapezoid(0, 0, 0.5, 1) }\n"
      "style s { spheres = \"red\"  v = triangle(0, 0.5, 1) }\n"
      "rule if a is x or not a is y and t is z and (a is x or t is z) then s is v\n",
      "t.rules");
  const Condition& c = base.rules.at(0).antecedent;
  ASSERT_EQ(c.op, Condition::Op::Or);
  ASSERT_EQ(c.operands.size(), 2u);
  const Condition& conjunction = c.operands[1];
  ASSERT_EQ(conjunction.op, Condition::Op::And);
  ASSERT_EQ(conjunction.operands.size(), 3u);
  EXPECT_EQ(conjunction.operands[0].op, Condition::Op::Not);
  EXPECT_EQ(conjunction.operands[2].op, Condition::Op::Or);
  EXPECT_EQ(base.rules[0].antecedent.position.column, 9);
}

TEST(Rules, ShapesAtKnownPoints) {
  const MembershipFunction trapezoid = shapeOf("trapezoid(0.2, 0.4, 0.6, 1.0)");
  EXPECT_EQ(trapezoid.at(0.0), 0.0);
  EXPECT_EQ(trapezoid.at(0.2), 0.0);
  EXPECT_DOUBLE_EQ(trapezoid.at(0.3), 0.5);
  EXPECT_EQ(trapezoid.at(0.4), 1.0);
  EXPECT_EQ(trapezoid.at(0.6), 1.0);
  EXPECT_DOUBLE_EQ(trapezoid.at(0.9), 0.25);
  EXPECT_EQ(trapezoid.at(1.0), 0.0);
  // Vertical edges: 1 at the edge itself.
  const MembershipFunction left = shapeOf("trapezoid(0, 0, 0.15, 0.3)");
  EXPECT_EQ(left.at(0.0), 1.0);
  EXPECT_EQ(left.at(-0.1), 0.0);
  const MembershipFunction right = shapeOf("trapezoid(0.25, 0.45, 1, 1)");
  EXPECT_EQ(right.at(1.0), 1.0);
  EXPECT_EQ(right.at(1.1), 0.0);

  const MembershipFunction triangle = shapeOf("triangle(0, 0.5, 0.75)");
  EXPECT_DOUBLE_EQ(triangle.at(0.25), 0.5);
  EXPECT_EQ(triangle.at(0.5), 1.0);
  EXPECT_DOUBLE_EQ(triangle.at(0.625), 0.5);

  const MembershipFunction gauss = shapeOf("gauss(0.5, 0.1)");
  EXPECT_EQ(gauss.at(0.5), 1.0);
  EXPECT_DOUBLE_EQ(gauss.at(0.6), std::exp(-0.5));
  EXPECT_DOUBLE_EQ(gauss.at(0.3), std::exp(-2.0));

  // points: linear between, constant beyond the ends.
  const MembershipFunction points = shapeOf("points((0.2, 0.1), (0.4, 0.9), (0.8, 0.5))");
  EXPECT_DOUBLE_EQ(points.at(0.0), 0.1);
  EXPECT_DOUBLE_EQ(points.at(0.3), 0.5);
  EXPECT_DOUBLE_EQ(points.at(0.6), 0.7);
  EXPECT_DOUBLE_EQ(points.at(1.0), 0.5);
  EXPECT_EQ(points.text(), "points((0.2, 0.1), (0.4, 0.9), (0.8, 0.5))");

  // A texture row: entry k at k / (size − 1).
  const std::vector<float> row = trapezoid.table(11);
  ASSERT_EQ(row.size(), 11u);
  EXPECT_FLOAT_EQ(row[3], 0.5f);
  EXPECT_FLOAT_EQ(row[9], 0.25f);
  EXPECT_EQ(trapezoid.at(std::nan("")), 0.0);
}

TEST(Rules, OneLineBlocksCommentsAndNumberForms) {
  const RuleBase base = parseRulesText(
      "attribute a from gradient{x=triangle(-.5,+0.5,1.5e0)}# comment\n"
      "style s priority 0{spheres=\"blue\" v=points((0,0),(1,1))}rule if a is x then s is v",
      "t.rules");
  EXPECT_EQ(base.attributes.at(0).values.at(0).function.parameters,
            (std::vector<double>{-0.5, 0.5, 1.5}));
  EXPECT_EQ(base.rules.size(), 1u);
}

// Lines ending in CR alone (old Mac files) read as those ending in LF or CR LF.
TEST(Rules, LinesEndAtLfCrLfOrCr) {
  const std::string text =
      "# a comment\nattribute a from gradient { x = triangle(0, 0.5, 1) }\n"
      "style s { spheres = \"blue\" v = points((0, 0), (1, 1)) }\n"
      "rule if a is x then s is v\n";
  for (const std::string ending : {"\r\n", "\r"}) {
    std::string changed;
    for (char c : text) changed += c == '\n' ? ending : std::string(1, c);
    const RuleBase base = parseRulesText(changed, "t.rules");
    EXPECT_EQ(base.rules.size(), 1u);
    EXPECT_EQ(base.rules.at(0).position.line, 4);
  }
}

// A UTF-8 byte-order mark before the text (a Windows editor's) is skipped.
TEST(Rules, AByteOrderMarkIsSkipped) {
  const std::string text =
      "attribute a from gradient { x = triangle(0, 0.5, 1) }\n"
      "style s { spheres = \"blue\" v = points((0, 0), (1, 1)) }\n"
      "rule if a is x then s is v\n";
  const RuleBase base = parseRulesText("\xEF\xBB\xBF" + text, "t.rules");
  EXPECT_EQ(base.rules.size(), 1u);
  EXPECT_EQ(base.attributes.at(0).name, parseRulesText(text, "t.rules").attributes.at(0).name);
}

TEST(Rules, SphereFilesResolveAgainstTheRuleFilesFolder) {
  const RuleBase base = parseRulesText(
      "style s { spheres = \"strips/Warm.PNG\"  v = triangle(0, 0.5, 1) }", "t.rules", "/data/x");
  EXPECT_EQ(base.styles.at(0).spheres.file, std::filesystem::path("/data/x/strips/Warm.PNG"));
  EXPECT_TRUE(base.styles[0].spheres.builtin.empty());
}

// Every class of bad input and the exact message it gives.
struct BadInput {
  const char* what;
  std::string text;
  std::string message;
};

const std::string kStyle = "style s { spheres = \"gray\"  v = triangle(0, 0.5, 1) }\n";
const std::string kAttribute = "attribute a from data { x = triangle(0, 0.5, 1) }\n";

void PrintTo(const BadInput& input, std::ostream* out) {
  *out << input.what;
}

class BadRules : public ::testing::TestWithParam<BadInput> {};

TEST_P(BadRules, GiveTheirExactMessage) {
  const std::string message = parseError(GetParam().text);
  EXPECT_EQ(message, GetParam().message) << GetParam().what;
  EXPECT_EQ(message.find('\n'), std::string::npos) << "one line: " << message;
}

INSTANTIATE_TEST_SUITE_P(
    Table, BadRules,
    ::testing::Values(
        // Syntax.
        BadInput{"top_level", "atribute a from data { }",
                 "t.rules:1:1: expected 'attribute', 'style', 'flatness' or 'rule', found "
                 "'atribute'"},
        BadInput{"missing_from", "attribute a data { x = triangle(0, 0.5, 1) }",
                 "t.rules:1:13: expected 'from' after the attribute name, found 'data'"},
        BadInput{"missing_brace", "attribute a from data x = triangle(0, 0.5, 1) }",
                 "t.rules:1:23: expected '{' to open the attribute's values, found 'x'"},
        BadInput{"missing_equals", kStyle + "attribute a from data {\n  x triangle(0, 0.5, 1) }",
                 "t.rules:3:5: expected '=' after the value name 'x', found 'triangle'"},
        BadInput{"missing_comma", "attribute a from data { x = triangle(0 0.5, 1) }",
                 "t.rules:1:40: expected ',' between the numbers of triangle, found 0.5"},
        BadInput{"unclosed_block", kStyle + "attribute a from data { x = triangle(0, 0.5, 1)",
                 "t.rules:2:48: expected a value name (name = shape(...)) or '}', found the end "
                 "of the file"},
        BadInput{"keyword_as_name", "attribute not from data { x = triangle(0, 0.5, 1) }",
                 "t.rules:1:11: expected an attribute name, found 'not'"},
        BadInput{"number_as_name", "style 3 { }", "t.rules:1:7: expected a style name, found 3"},
        BadInput{"unexpected_character", kStyle + "rule if a is x then s is v;",
                 "t.rules:2:27: unexpected character ';'"},
        BadInput{"control_character", std::string("style s\x01 { }"),
                 "t.rules:1:8: unexpected character '\\x01'"},
        BadInput{"unclosed_string", "style s { spheres = \"gray }\n",
                 "t.rules:1:21: string not closed on its line"},
        BadInput{"spheres_not_a_string", "style s { spheres = gray }",
                 "t.rules:1:21: expected a string (a built-in ramp or a .png file), found 'gray'"},
        BadInput{"rule_without_then", kStyle + kAttribute + "rule if a is x s is v",
                 "t.rules:3:16: expected 'then' after the condition, found 's'"},
        BadInput{"rule_without_is", kStyle + kAttribute + "rule if a x then s is v",
                 "t.rules:3:11: expected 'is' after the attribute name 'a', found 'x'"},
        BadInput{"dangling_and", kStyle + kAttribute + "rule if a is x and then s is v",
                 "t.rules:3:20: expected an attribute name, 'not' or '(' in the condition, found "
                 "'then'"},
        BadInput{"unclosed_parenthesis", kStyle + kAttribute + "rule if (a is x then s is v",
                 "t.rules:3:17: expected ')' to close the '(' at line 3, column 9, found 'then'"},
        BadInput{"points_without_pairs", "style s { spheres = \"gray\"  v = points(0, 0.5) }",
                 "t.rules:1:40: expected '(' to open a point (x, y), found 0"},
        // Unknown sources, shapes, ramps.
        BadInput{"unknown_source", "attribute a from dta { x = triangle(0, 0.5, 1) }",
                 "t.rules:1:18: unknown source 'dta' (known: data, gradient, cursor_distance, "
                 "plane_distance, image_distance, view_angle, time)"},
        BadInput{"unknown_shape", "attribute a from data { x = trapez(0, 0.5, 1) }",
                 "t.rules:1:29: unknown shape 'trapez' (known: trapezoid, triangle, gauss, "
                 "points)"},
        BadInput{"unknown_ramp", "style s { spheres = \"ivry\"  v = triangle(0, 0.5, 1) }",
                 "t.rules:1:21: unknown sphere ramp 'ivry' (built in: gray, ivory, skin, red, "
                 "green, blue; or a .png file)"},
        // Argument counts.
        BadInput{"trapezoid_args", "attribute a from data { x = trapezoid(0, 0.5, 1) }",
                 "t.rules:1:29: trapezoid takes 4 numbers (a, b, c, d), found 3"},
        BadInput{"triangle_args", "attribute a from data { x = triangle() }",
                 "t.rules:1:29: triangle takes 3 numbers (a, b, c), found 0"},
        BadInput{"gauss_args", "attribute a from data { x = gauss(0.5, 0.1, 3) }",
                 "t.rules:1:29: gauss takes 2 numbers (mean, sd), found 3"},
        BadInput{"points_args", "attribute a from data { x = points((0.5, 1)) }",
                 "t.rules:1:29: points takes 2 to 64 points (x, y), found 1"},
        // Unknown names in rules.
        BadInput{"unknown_attribute", kStyle + kAttribute + "rule if dens is x then s is v",
                 "t.rules:3:9: unknown attribute 'dens' (known: a)"},
        BadInput{"unknown_attribute_value", kStyle + kAttribute + "rule if a is hi then s is v",
                 "t.rules:3:14: attribute 'a' has no value 'hi' (it has x)"},
        BadInput{"unknown_style", kStyle + kAttribute + "rule if a is x then bone is v",
                 "t.rules:3:21: unknown style 'bone' (known: s)"},
        BadInput{"unknown_style_value", kStyle + kAttribute + "rule if a is x then s is opaque",
                 "t.rules:3:26: style 's' has no value 'opaque' (it has v)"},
        BadInput{"no_flatness_block", kStyle + kAttribute + "rule if a is x then flatness is v",
                 "t.rules:3:21: no flatness block defines the flatness values"},
        BadInput{"unknown_flatness_value",
                 kStyle + kAttribute + "flatness { high = triangle(0.5, 1, 1) }\n" +
                     "rule if a is x then flatness is low",
                 "t.rules:4:33: the flatness block has no value 'low' (it has high)"},
        // Empty and inverted shapes.
        BadInput{"inverted_trapezoid",
                 "attribute a from data { x = trapezoid(0.3, 0.2, 0.4, 0.5) }",
                 "t.rules:1:29: trapezoid(0.3, 0.2, 0.4, 0.5) is inverted: needs a <= b <= c <= d"},
        BadInput{"inverted_triangle", "attribute a from data { x = triangle(0.5, 0.4, 1) }",
                 "t.rules:1:29: triangle(0.5, 0.4, 1) is inverted: needs a <= b <= c"},
        BadInput{"gauss_zero_sd", "attribute a from data { x = gauss(0.5, 0) }",
                 "t.rules:1:29: gauss(0.5, 0) needs sd >= 0.001"},
        BadInput{"points_not_increasing",
                 "attribute a from data { x = points((0.1, 0), (0.4, 1), (0.2, 0)) }",
                 "t.rules:1:56: points: x must increase, but point 3 has x 0.2 after 0.4"},
        BadInput{"points_y_outside", "attribute a from data { x = points((0.1, 0), (0.4, 1.5)) }",
                 "t.rules:1:52: points: y of point 2 must be in [0, 1], found 1.5"},
        BadInput{"attribute_value_outside", "attribute a from data { x = trapezoid(2, 3, 4, 5) }",
                 "t.rules:1:25: trapezoid(2, 3, 4, 5) is zero everywhere on [0, 1]"},
        BadInput{"style_value_empty", "style s { spheres = \"gray\"  v = triangle(0.5, 0.5, 0.5) }",
                 "t.rules:1:29: triangle(0.5, 0.5, 0.5) is (almost) zero on [0, 1]: its integral 0 "
                 "is below 0.001 (the centroid divides by it)"},
        BadInput{"empty_attribute", "attribute a from data { }",
                 "t.rules:1:11: attribute 'a' has no values"},
        BadInput{
            "style_without_spheres", "style s { v = triangle(0, 0.5, 1) }",
            "t.rules:1:7: style 's' has no spheres = \"...\" (a built-in ramp or a .png file)"},
        BadInput{"no_style", kAttribute,
                 "t.rules:1:1: no style defined (a rule base needs at least one)"},
        // Duplicate names.
        BadInput{"duplicate_attribute", kAttribute + kAttribute,
                 "t.rules:2:11: attribute 'a' is defined twice (first at line 1)"},
        BadInput{"duplicate_value",
                 "attribute a from data {\n x = triangle(0, 0.5, 1)\n "
                 "x = gauss(0.5, 0.2) }",
                 "t.rules:3:2: value 'x' is defined twice in attribute 'a' (first at line 2)"},
        BadInput{"duplicate_style", kStyle + kStyle,
                 "t.rules:2:7: style 's' is defined twice (first at line 1)"},
        BadInput{"duplicate_spheres", "style s { spheres = \"gray\" spheres = \"red\" }",
                 "t.rules:1:28: spheres given twice in style 's' (first at line 1)"},
        BadInput{"duplicate_flatness", "flatness { v = triangle(0, 0.5, 1) }\nflatness { }",
                 "t.rules:2:1: flatness block given twice (first at line 1)"},
        // Numbers.
        BadInput{"infinite_number", "attribute a from data { x = triangle(0, 1e999, 1) }",
                 "t.rules:1:41: number 1e999 is out of range (not a finite double)"},
        BadInput{"nan_number", "attribute a from data { x = triangle(0, nan, 1) }",
                 "t.rules:1:41: expected a number, found 'nan'"},
        BadInput{"fractional_priority", "style s priority 2.5 { }",
                 "t.rules:1:18: priority must be an integer from 0 to 1000, found 2.5"},
        BadInput{"exponent_priority", "style s priority 1e2 { }",
                 "t.rules:1:18: priority must be an integer from 0 to 1000, found 1e2"},
        // Lines end at a lone CR too (old Mac files): the comment ends there and the error is
        // on line 2.
        BadInput{"cr_line_ends", "# comment\rstyle s priority 1.5 { }",
                 "t.rules:2:18: priority must be an integer from 0 to 1000, found 1.5"},
        // Sizes.
        BadInput{"too_deep", kStyle + kAttribute + "rule if " + std::string(40, '(') + "a is x",
                 "t.rules:3:41: condition nested deeper than 32 (not and parentheses; the limit)"},
        BadInput{"long_string", "style s { spheres = \"" + std::string(2000, 'x') + ".png\" }",
                 "t.rules:1:21: string of 2004 bytes, more than the 1024 allowed"}),
    [](const ::testing::TestParamInfo<BadInput>& info) { return std::string(info.param.what); });

TEST(Rules, SizeLimitsAreStated) {
  std::string many = kStyle + kAttribute;
  for (int i = 0; i < 257; ++i) many += "rule if a is x then s is v\n";
  EXPECT_EQ(parseError(many), "t.rules:259:1: more than 256 rules (the limit)");

  std::string terms = kStyle + kAttribute + "rule if a is x";
  for (int i = 0; i < 64; ++i) terms += " or a is x";
  EXPECT_EQ(parseError(terms + " then s is v"),
            "t.rules:3:649: rule has more than 64 terms (the limit)");

  std::string huge(limits::kMaxHeaderBytes + 1, ' ');
  EXPECT_EQ(parseError(huge), "t.rules: rule text of 1048577 bytes, more than the 1048576 allowed");
}

TEST(Rules, UnreachedStylesAndUnusedAttributesAreWarnings) {
  const RuleBase base = parseRulesText(
      kAttribute + "attribute b from time { y = triangle(0, 0.5, 1) }\n" + kStyle +
          "style lonely priority 3 { spheres = \"green\"  v = triangle(0, 0.5, 1) }\n" +
          "flatness { f = triangle(0, 0.5, 1) }\n" + "rule if a is x then s is v\n",
      "t.rules");
  EXPECT_EQ(base.warnings,
            (std::vector<std::string>{
                "t.rules:2:11: warning: attribute 'b' is used by no rule",
                "t.rules:4:7: warning: style 'lonely' is reached by no rule (never drawn)",
                "t.rules:5:1: warning: the flatness block is reached by no rule (flatness stays "
                "0)"}));
}

TEST(Rules, TheShippedExamplesParseWithoutWarnings) {
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(kRulesDir)) {
    if (entry.path().extension() != ".rules") continue;
    ++files;
    SCOPED_TRACE(entry.path().string());
    RuleBase base;
    ASSERT_NO_THROW(base = loadRules(entry.path().string()));
    EXPECT_FALSE(base.rules.empty());
    EXPECT_TRUE(base.warnings.empty()) << base.warnings.front();
  }
  EXPECT_GE(files, 3);
}

TEST(Rules, LoadingNamesTheFile) {
  const std::string missing = (kRulesDir / "no-such.rules").string();
  try {
    loadRules(missing);
    FAIL() << "no error";
  } catch (const InputError& error) {
    EXPECT_EQ(std::string(error.what()).rfind(missing + ": ", 0), 0u) << error.what();
  }
}

// The tables against integrals computed by hand for triangle(0, 0.5, 1): truncated at d it is a
// trapezoid of height d with top [d/2, 1 − d/2], area d − d²/2, centroid 0.5 by symmetry.
TEST(DefuzzTables, MatchHandIntegrals) {
  const RuleBase base = parseRulesText(
      kAttribute +
          "style s { spheres = \"gray\"  v = triangle(0, 0.5, 1)  w = trapezoid(0.5, 0.5, "
          "1, 1) }\nrule if a is x then s is v\nrule if a is x then s is w\n",
      "t.rules");
  const DefuzzTables tables = buildDefuzzTables(base, 256);
  ASSERT_EQ(tables.size, 256);
  ASSERT_EQ(tables.rows, 2);
  ASSERT_EQ(tables.numerator.size(), 512u);
  EXPECT_EQ(tables.firstRow, (std::vector<int>{0, 2}));
  EXPECT_EQ(tables.row(base.rules[1]), 1);
  // Midpoint integration of piecewise linear shapes with 16384 steps: errors far below 1e-6.
  constexpr double kIntegration = 1e-6;
  // At the table's own degrees k/255 (between them see below).
  for (double d : {0.0, 51 / 255.0, 128 / 255.0, 1.0}) {
    EXPECT_NEAR(tables.denominatorAt(0, d), d - d * d / 2, kIntegration) << d;
    EXPECT_NEAR(tables.numeratorAt(0, d), 0.5 * (d - d * d / 2), kIntegration) << d;
    // w: a box [0.5, 1] truncated at d: area d/2, moment d·(1 − 0.25)/2.
    EXPECT_NEAR(tables.denominatorAt(1, d), d / 2, kIntegration) << d;
    EXPECT_NEAR(tables.numeratorAt(1, d), d * 0.375, kIntegration) << d;
  }
  // Between entries: linear interpolation of the quadratic d − d²/2, off by at most h²/8 · 1.
  const double h = 1.0 / 255.0;
  EXPECT_NEAR(tables.denominatorAt(0, 0.3), 0.3 - 0.045, h * h / 8 + kIntegration);
  // Both rules at degree 1: (0.5·0.5 + 0.375) / (0.5 + 0.5) = 0.625.
  const RuleActivation both[] = {{0, 1.0}, {1, 1.0}};
  EXPECT_NEAR(tableCentroid(tables, both), 0.625, kIntegration);
  const RuleActivation none[] = {{0, 0.0}, {1, 0.0}};
  EXPECT_EQ(tableCentroid(tables, none), 0.0);
}

// --rules takes rule text itself (it holds an attribute block's '{'; the Python package's
// rules="..."): the same rule base as the file, errors named "--rules:LINE:COLUMN".
TEST(Rules, TheOptionTakesRuleTextItself) {
  const std::string text = io::readWholeFile((kRulesDir / "example.rules").string(), 1 << 20);
  const RuleBase inline_ = loadRulesPreset(text);
  const RuleBase preset = loadRulesPreset("example");
  EXPECT_EQ(inline_.rules.size(), preset.rules.size());
  EXPECT_EQ(inline_.attributes.size(), preset.attributes.size());
  EXPECT_EQ(inline_.styles.size(), preset.styles.size());
  try {
    loadRulesPreset("attribute a from data { }\nrule if");
    FAIL() << "a broken rule base was taken";
  } catch (const InputError& error) {
    EXPECT_EQ(std::string(error.what()).rfind("--rules:", 0), 0u) << error.what();
  }
}

}  // namespace
}  // namespace vsil
