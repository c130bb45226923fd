// Rule bases (`.rules` files of technique `semantic`, core/rules.h): the lexer, the parser with
// its name resolution and checks, and, for bases of a few values, the defuzzification tables.
#include "core/rules.h"
#include "fuzz_target.h"

VSIL_FUZZ_TARGET(rules) {
  const vsil::fuzz::InputFile file(bytes, ".rules");
  const vsil::RuleBase base = vsil::loadRules(file.path());
  (void)base.usedSources();
  // Tables cost a fixed integration per value (about 1 ms): enough values to cover the layout,
  // few enough that one input stays far from the fuzzer's time limit.
  constexpr std::size_t kMaxTabulatedValues = 16;
  std::size_t values = base.flatness.size();
  for (const auto& style : base.styles) values += style.values.size();
  if (values <= kMaxTabulatedValues) (void)vsil::buildDefuzzTables(base, 16);
}
