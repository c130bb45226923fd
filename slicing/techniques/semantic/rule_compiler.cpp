#include "slicing/techniques/semantic/rule_compiler.h"

#include <algorithm>
#include <map>
#include <utility>

namespace vsil {

namespace {

// Text a GLSL line comment may hold: printable ASCII but the backslash (a line continuation),
// anything else '?'. A newline in a rule file's name would otherwise start shader code.
std::string glslCommentText(const std::string& text) {
  std::string out = text;
  for (char& c : out) {
    if (c < 0x20 || c > 0x7e || c == '\\') c = '?';
  }
  return out;
}

// The GLSL global each source's normalized value is in (semantic.frag sets the used ones).
constexpr std::array<const char*, kAttributeSourceCount> kSourceVariables = {
    "semanticData",          "semanticGradient",      "semanticCursorDistance",
    "semanticPlaneDistance", "semanticImageDistance", "semanticViewAngle",
    "semanticTime"};
constexpr std::array<const char*, kAttributeSourceCount> kSourceDefines = {
    "SEMANTIC_SOURCE_DATA",
    "SEMANTIC_SOURCE_GRADIENT",
    "SEMANTIC_SOURCE_CURSOR_DISTANCE",
    "SEMANTIC_SOURCE_PLANE_DISTANCE",
    "SEMANTIC_SOURCE_IMAGE_DISTANCE",
    "SEMANTIC_SOURCE_VIEW_ANGLE",
    "SEMANTIC_SOURCE_TIME"};

// The rule's antecedent as the file could have written it (for the generated comments).
std::string conditionText(const RuleBase& rules, const Condition& condition, bool nested) {
  switch (condition.op) {
    case Condition::Op::Is: {
      const Attribute& attribute = rules.attributes[std::size_t(condition.attribute)];
      return attribute.name + " is " + attribute.values[std::size_t(condition.value)].name;
    }
    case Condition::Op::Not:
      return "not " + conditionText(rules, condition.operands.front(), true);
    case Condition::Op::And:
    case Condition::Op::Or: {
      std::string text;
      const char* word = condition.op == Condition::Op::And ? " and " : " or ";
      for (const auto& operand : condition.operands) {
        text += (text.empty() ? "" : word) + conditionText(rules, operand, true);
      }
      return nested ? "(" + text + ")" : text;
    }
  }
  return "";
}

std::string floatText(int value) {
  return std::to_string(value);
}

// A GLSL expression for the condition's degree; terms are the variables m<row>.
std::string conditionGlsl(const Condition& condition, const MembershipTables& membership) {
  switch (condition.op) {
    case Condition::Op::Is:
      return "m" + std::to_string(membership.firstRow[std::size_t(condition.attribute)] +
                                  condition.value);
    case Condition::Op::Not:
      return "(1.0 - " + conditionGlsl(condition.operands.front(), membership) + ")";
    case Condition::Op::And:
    case Condition::Op::Or: {
      // min(a, min(b, c)): the same value as the reference's left-to-right fold (min and max are
      // exact in float).
      const char* function = condition.op == Condition::Op::And ? "min(" : "max(";
      std::string text = conditionGlsl(condition.operands.back(), membership);
      for (std::size_t i = condition.operands.size() - 1; i-- > 0;) {
        text = function + conditionGlsl(condition.operands[i], membership) + ", " + text + ")";
      }
      return text;
    }
  }
  return "0.0";
}

void collectTerms(const Condition& condition, const MembershipTables& membership,
                  std::map<int, std::pair<int, int>>& terms) {
  if (condition.op == Condition::Op::Is) {
    const int row = membership.firstRow[std::size_t(condition.attribute)] + condition.value;
    terms.emplace(row, std::make_pair(condition.attribute, condition.value));
  }
  for (const auto& operand : condition.operands) collectTerms(operand, membership, terms);
}

// The range [low, high] a condition's degree can take for data values in one table interval.
struct DegreeBounds {
  float low = 0, high = 1;
};

DegreeBounds conditionBounds(const RuleBase& rules, const Condition& condition,
                             const MembershipTables& membership, int interval) {
  switch (condition.op) {
    case Condition::Op::Is: {
      const int row = membership.firstRow[std::size_t(condition.attribute)] + condition.value;
      const float* entries = membership.entries.data() + std::size_t(row) * membership.size;
      const Attribute& attribute = rules.attributes[std::size_t(condition.attribute)];
      if (attribute.source == AttributeSource::Data) {
        // Linear between two entries: the degree lies between them.
        const float a = entries[interval], b = entries[interval + 1];
        return {std::min(a, b), std::max(a, b)};
      }
      const auto [low, high] = std::minmax_element(entries, entries + membership.size);
      return {*low, *high};
    }
    case Condition::Op::Not: {
      const DegreeBounds inner =
          conditionBounds(rules, condition.operands.front(), membership, interval);
      return {1.0f - inner.high, 1.0f - inner.low};
    }
    case Condition::Op::And:
    case Condition::Op::Or: {
      const bool isAnd = condition.op == Condition::Op::And;
      DegreeBounds bounds = isAnd ? DegreeBounds{1, 1} : DegreeBounds{0, 0};
      for (const auto& operand : condition.operands) {
        const DegreeBounds b = conditionBounds(rules, operand, membership, interval);
        bounds = isAnd ? DegreeBounds{std::min(bounds.low, b.low), std::min(bounds.high, b.high)}
                       : DegreeBounds{std::max(bounds.low, b.low), std::max(bounds.high, b.high)};
      }
      return bounds;
    }
  }
  return {};
}

}  // namespace

float MembershipTables::at(int row, float x) const {
  const float t = std::clamp(x, 0.0f, 1.0f) * float(size - 1);
  const int k = std::min(int(t), size - 2);
  const float f = t - float(k);
  const float* e = entries.data() + std::size_t(row) * std::size_t(size);
  return e[k] * (1.0f - f) + e[k + 1] * f;  // GLSL mix(a, b, f)
}

MembershipTables buildMembershipTables(const RuleBase& rules, int size) {
  MembershipTables tables;
  tables.size = std::max(size, 2);
  for (const Attribute& attribute : rules.attributes) {
    tables.firstRow.push_back(tables.rows);
    for (const SemanticValue& value : attribute.values) {
      const std::vector<float> row = value.function.table(tables.size);
      tables.entries.insert(tables.entries.end(), row.begin(), row.end());
      ++tables.rows;
    }
  }
  return tables;
}

std::vector<std::uint8_t> visibleDataIntervals(const RuleBase& rules,
                                               const MembershipTables& membership) {
  std::vector<std::uint8_t> visible(std::size_t(membership.size - 1), 0);
  for (int k = 0; k + 1 < membership.size; ++k) {
    for (const Rule& rule : rules.rules) {
      if (rule.flatness) continue;  // the flatness adds no opacity
      if (conditionBounds(rules, rule.antecedent, membership, k).high > 0.0f) {
        visible[std::size_t(k)] = 1;
        break;
      }
    }
  }
  return visible;
}

CompiledRules compileRules(const RuleBase& rules) {
  CompiledRules compiled;
  compiled.sources = rules.usedSources();
  compiled.styleCount = int(rules.styles.size());
  const MembershipTables layout = buildMembershipTables(rules, 2);  // rows only
  DefuzzTables defuzzLayout;  // the rows only (buildDefuzzTables' order), nothing integrated
  for (const Style& style : rules.styles) {
    defuzzLayout.firstRow.push_back(defuzzLayout.rows);
    defuzzLayout.rows += int(style.values.size());
  }
  defuzzLayout.firstRow.push_back(defuzzLayout.rows);

  std::string& out = compiled.glsl;
  out += "// Generated by vsil's rule compiler from " + glslCommentText(rules.source) + ": " +
         std::to_string(rules.rules.size()) + " rules, " + std::to_string(rules.styles.size()) +
         " styles. Do not edit.\n";
  for (int s = 0; s < kAttributeSourceCount; ++s) {
    if (compiled.sources[std::size_t(s)]) {
      out += "#define " + std::string(kSourceDefines[std::size_t(s)]) + "\n";
    }
  }
  out += "#define SEMANTIC_STYLE_COUNT " + std::to_string(std::max(compiled.styleCount, 1)) + "\n";
  for (const Rule& rule : rules.rules) compiled.flatnessRules |= rule.flatness;
  if (compiled.flatnessRules) out += "#define SEMANTIC_FLATNESS_RULES\n";
  out +=
      "\nvoid semanticEvaluate(out float weight[SEMANTIC_STYLE_COUNT],\n"
      "                      out float value[SEMANTIC_STYLE_COUNT], out vec2 flatness) {\n";

  // Each term once: the membership of its source's value.
  std::map<int, std::pair<int, int>> terms;  // row -> (attribute, value)
  for (const Rule& rule : rules.rules) collectTerms(rule.antecedent, layout, terms);
  for (const auto& [row, term] : terms) {
    const Attribute& attribute = rules.attributes[std::size_t(term.first)];
    out += "  float m" + std::to_string(row) + " = semanticMembership(" + floatText(row) + ", " +
           kSourceVariables[std::size_t(attribute.source)] + ");  // " + attribute.name + " is " +
           attribute.values[std::size_t(term.second)].name + "\n";
  }
  // Each rule's degree.
  for (std::size_t i = 0; i < rules.rules.size(); ++i) {
    const Rule& rule = rules.rules[i];
    out += "  // " +
           glslCommentText(rules.source + ":" + std::to_string(rule.position.line) + ": if " +
                           conditionText(rules, rule.antecedent, false) + " then " + rule.target +
                           " is " + rule.valueName) +
           "\n";
    out += "  float r" + std::to_string(i) + " = " + conditionGlsl(rule.antecedent, layout) + ";\n";
  }
  // Each consequent: Σ (N, D) over its rules in file order, the largest degree.
  const auto consequent = [&](bool flatness, int style, const std::string& weightOut,
                              const std::string& valueOut, const std::string& name) {
    std::string sum, weight;
    for (std::size_t i = 0; i < rules.rules.size(); ++i) {
      const Rule& rule = rules.rules[i];
      if (rule.flatness != flatness || (!flatness && rule.style != style)) continue;
      const std::string r = "r" + std::to_string(i);
      const std::string lookup =
          "semanticDefuzz(" + std::to_string(defuzzLayout.row(rule)) + ", " + r + ")";
      sum = sum.empty() ? lookup : sum + " + " + lookup;
      weight = weight.empty() ? r : "max(" + weight + ", " + r + ")";
    }
    out += "  // " + name + "\n";
    if (sum.empty()) {
      out += "  " + weightOut + " = 0.0;\n  " + valueOut + " = 0.0;\n";
      return;
    }
    out += "  {\n    vec2 nd = " + sum + ";\n";
    out += "    " + weightOut + " = " + weight + ";\n";
    out += "    " + valueOut + " = nd.y > 0.0 ? nd.x / nd.y : 0.0;\n  }\n";
  };
  for (std::size_t s = 0; s < rules.styles.size(); ++s) {
    const std::string index = "[" + std::to_string(s) + "]";
    consequent(false, int(s), "weight" + index, "value" + index, "style " + rules.styles[s].name);
  }
  if (rules.styles.empty()) out += "  weight[0] = 0.0;\n  value[0] = 0.0;\n";
  consequent(true, -1, "flatness.x", "flatness.y", "flatness");
  out += "}\n";
  return compiled;
}

}  // namespace vsil
