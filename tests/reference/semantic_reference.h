#pragma once
// The CPU reference of the fuzzy pipeline of technique `semantic` (Rautek et al., the paper's
// equations 1-6 in papers/README.md), written from the paper, not from the shaders or the
// tables: each rule's antecedent degree from the membership functions themselves, then per style
// (and for the flatness) the aggregated function f(x) = Σ_i min(m_i(x), a_i) of the rules that
// reach it, and its centroid ∫ x f / ∫ f by direct numerical integration over [0, 1].
//
// The weight of a style (its activation): the largest degree among the rules that reach it,
// max_i a_i, in [0, 1]. The centroid says where on its sphere ramp a sample lies, the weight how
// much of the style it carries: 0 where no rule fires (the style contributes nothing there and
// its value is reported as 0), 1 where some rule holds fully. The max, not the sum, so that two
// rules saying the same thing do not count twice and the weight stays a degree of truth; it is
// also the height of the aggregated function where the consequents do not overlap. The flatness
// has a weight the same way; where it is 0 the flatness value is 0 (ordinary compositing).
#include <vector>

#include "core/rules.h"

namespace vsil::reference {

// A consequent's defuzzified value and weight at one sample.
struct FuzzyOutput {
  double value = 0;   // the centroid, in [0, 1]; 0 where weight is 0
  double weight = 0;  // max of the degrees of the rules that reach it
};

struct SemanticSample {
  std::vector<double> ruleDegrees;  // per rule, its antecedent's degree
  std::vector<FuzzyOutput> styles;  // per style, in RuleBase::styles order
  FuzzyOutput flatness;
};

// The degree of `condition` for the normalized inputs: and = min, or = max, not = 1 − x.
double conditionDegree(const RuleBase& rules, const Condition& condition,
                       const AttributeInputs& inputs);

// The centroid of Σ min(functions[i](x), degrees[i]) on [0, 1], integrated with the midpoint
// rule on kReferenceSteps intervals (0 where the integral is 0).
inline constexpr int kReferenceSteps = 20000;
double directCentroid(const std::vector<const MembershipFunction*>& functions,
                      const std::vector<double>& degrees);

SemanticSample evaluateSemantic(const RuleBase& rules, const AttributeInputs& inputs);

}  // namespace vsil::reference
