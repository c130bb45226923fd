#pragma once
// The rule compiler of technique `semantic` (Rautek et al. 2008, section 4): a rule base
// (core/rules.h) becomes GLSL that the slice shader's template (semantic.glsl, semantic.frag)
// calls once per sample. The generated code holds only the rule base's structure: which terms
// each rule combines with min, max and 1 − x, which table row each term and each consequent
// reads, which sources are computed (RuleBase::usedSources). The numbers live in data:
//   - membership functions: one row of kMembershipTableSize entries per attribute value
//     (MembershipTables), as a texture of its segments (entries k and k + 1 in one RG32F
//     texel), read with one texelFetch and a mix;
//   - defuzzification: DefuzzTables (core/rules.h) likewise, (N, D) at k and k + 1 per RGBA32F
//     texel;
//   - styles: priorities, layer order and lit-sphere ramps as uniforms and a 3D texture.
// So changing a membership function (even its shape), a priority or a sphere ramp uploads data
// and never recompiles; only a change of the rules themselves does.
//
// The generated function, for the template:
//   void semanticEvaluate(out float weight[SEMANTIC_STYLE_COUNT],
//                         out float value[SEMANTIC_STYLE_COUNT], out vec2 flatness)
// reads the inputs semanticData, semanticGradient, ... (globals the template sets, only those of
// the #defined SEMANTIC_SOURCE_*), and gives per style its weight (the largest degree of the
// rules that reach it) and defuzzified value (Σ N / Σ D, 0 where no rule fires), and the
// flatness' (weight, value). No GL here: `vsil rules --glsl` prints the same text.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/rules.h"

namespace vsil {

// kMembershipTableSize (core/rules.h): entries per membership-function row.

// The membership functions of every attribute value, row after row (attribute by attribute, its
// values in order); uploaded as their segments (semantic_technique.cpp tableSegments).
struct MembershipTables {
  int size = 0;
  int rows = 0;
  std::vector<float> entries;  // rows × size
  std::vector<int> firstRow;   // per attribute, its value 0's row

  // What the shader's semanticMembership() computes, in float: the entries around x (clamped to
  // [0, 1]) mixed.
  float at(int row, float x) const;
};
MembershipTables buildMembershipTables(const RuleBase& rules, int size = kMembershipTableSize);

// Which values of the data source may show something: interval k covers normalized data values
// between table entries k and k + 1. False where every rule that reaches a style has degree 0
// for every data value in the interval, whatever the other sources are (their terms count as
// anything their membership rows allow). Empty-space skipping and the shader's early exit read it.
std::vector<std::uint8_t> visibleDataIntervals(const RuleBase& rules,
                                               const MembershipTables& membership);

struct CompiledRules {
  std::string glsl;  // the generated source (the template includes it before main)
  std::array<bool, kAttributeSourceCount> sources{};
  int styleCount = 0;
  bool flatnessRules = false;  // some rule sets the flatness
};
CompiledRules compileRules(const RuleBase& rules);

}  // namespace vsil
