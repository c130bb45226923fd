#include "semantic_reference.h"

#include <algorithm>

namespace vsil::reference {

double conditionDegree(const RuleBase& rules, const Condition& condition,
                       const AttributeInputs& inputs) {
  switch (condition.op) {
    case Condition::Op::Is: {
      const Attribute& attribute = rules.attributes[std::size_t(condition.attribute)];
      const double x = inputs[std::size_t(attribute.source)];
      return attribute.values[std::size_t(condition.value)].function.at(x);
    }
    case Condition::Op::Not:
      return 1.0 - conditionDegree(rules, condition.operands.front(), inputs);
    case Condition::Op::And: {
      double degree = 1.0;
      for (const auto& operand : condition.operands) {
        degree = std::min(degree, conditionDegree(rules, operand, inputs));
      }
      return degree;
    }
    case Condition::Op::Or: {
      double degree = 0.0;
      for (const auto& operand : condition.operands) {
        degree = std::max(degree, conditionDegree(rules, operand, inputs));
      }
      return degree;
    }
  }
  return 0.0;
}

double directCentroid(const std::vector<const MembershipFunction*>& functions,
                      const std::vector<double>& degrees) {
  double moment = 0.0, area = 0.0;
  for (int step = 0; step < kReferenceSteps; ++step) {
    const double x = (step + 0.5) / kReferenceSteps;
    double f = 0.0;  // the aggregated function: the sum of the truncated consequents
    for (std::size_t i = 0; i < functions.size(); ++i) {
      f += std::min(functions[i]->at(x), degrees[i]);
    }
    moment += x * f;
    area += f;
  }
  return area > 0.0 ? moment / area : 0.0;
}

SemanticSample evaluateSemantic(const RuleBase& rules, const AttributeInputs& inputs) {
  SemanticSample sample;
  for (const Rule& rule : rules.rules) {
    sample.ruleDegrees.push_back(conditionDegree(rules, rule.antecedent, inputs));
  }
  // One consequent: the rules that reach it, their values' functions and degrees.
  const auto defuzzify = [&](bool flatness, int style, const std::vector<SemanticValue>& values) {
    std::vector<const MembershipFunction*> functions;
    std::vector<double> degrees;
    FuzzyOutput output;
    for (std::size_t i = 0; i < rules.rules.size(); ++i) {
      const Rule& rule = rules.rules[i];
      if (rule.flatness != flatness || (!flatness && rule.style != style)) continue;
      functions.push_back(&values[std::size_t(rule.value)].function);
      degrees.push_back(sample.ruleDegrees[i]);
      output.weight = std::max(output.weight, sample.ruleDegrees[i]);
    }
    if (output.weight > 0.0) output.value = directCentroid(functions, degrees);
    return output;
  };
  for (std::size_t s = 0; s < rules.styles.size(); ++s) {
    sample.styles.push_back(defuzzify(false, int(s), rules.styles[s].values));
  }
  sample.flatness = defuzzify(true, -1, rules.flatness);
  return sample;
}

}  // namespace vsil::reference
