// `vsil rules FILE`: a rule base (a .rules file or a preset) checked as `render --technique
// semantic` reads it — parsed, its sphere ramps loaded, compiled — and summarized; --glsl prints
// the generated shader code instead, --check prints nothing but warnings (exit 0: it is valid).
// No OpenGL: the generated code is the rule compiler's text (slicing/techniques/semantic/).
#include <iostream>
#include <memory>

#include "cli/commands.h"
#include "core/rules.h"
#include "slicing/techniques/semantic/rule_compiler.h"
#include "slicing/techniques/semantic/sphere_atlas.h"

namespace vsil::cli {
namespace {

struct RulesFlags {
  std::string input;
  bool glsl = false;
  bool check = false;
};

void runRules(const RulesFlags& flags) {
  if (validateOnly()) return;
  const RuleBase rules = loadRulesPreset(flags.input, "rules FILE");
  buildSphereAtlas(rules);  // the sphere files must read
  const CompiledRules compiled = compileRules(rules);
  for (const auto& warning : rules.warnings) std::cerr << "vsil: " << warning << "\n";
  if (flags.check) return;
  if (flags.glsl) {
    std::cout << compiled.glsl;
    return;
  }
  std::cout << rules.source << ": " << rules.rules.size() << " rules, " << rules.attributes.size()
            << " attributes, " << rules.styles.size() << " styles"
            << (compiled.flatnessRules ? ", flatness rules (flat rendering mode)" : "") << "\n";
  std::cout << "sources:";
  const auto used = rules.usedSources();
  for (int s = 0; s < kAttributeSourceCount; ++s) {
    if (used[std::size_t(s)]) std::cout << " " << attributeSourceName(AttributeSource(s));
  }
  std::cout << "\n";
  for (const Style& style : rules.styles) {
    std::cout << "style " << style.name << " priority " << style.priority << " spheres \""
              << style.spheres.text << "\"\n";
  }
  std::cout << "generated GLSL: " << compiled.glsl.size() << " bytes (--glsl prints it)\n";
}

const CommandRegistration registerRulesCommand(60, [](CLI::App& app) {
  auto flags = std::make_shared<RulesFlags>();
  CLI::App* command = app.add_subcommand(
      "rules", "Check a fuzzy rule base (technique semantic) and show what it compiles to");
  command->add_option("FILE", flags->input, "a .rules file or a preset name")->required();
  command->add_flag("--glsl", flags->glsl, "print the generated shader code");
  command->add_flag("--check", flags->check, "only validate (warnings to stderr)");
  command->callback([flags] { runRules(*flags); });
});

}  // namespace
}  // namespace vsil::cli
