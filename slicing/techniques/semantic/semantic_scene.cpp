#include "slicing/techniques/semantic/semantic_scene.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "core/error.h"
#include "core/transfer_function.h"

namespace vsil {

namespace {

// Not given, the flatness rules decide per sample; given, one flatness everywhere. No value
// stands for "not given" (0 is ordinary compositing everywhere, which ignores the rules), so
// the option declares none: the help, the metadata (null) and Python's default (None) say so.
OptionSpec flatnessOption() {
  OptionSpec spec = OptionSpec::number("flatness", 0.0,
                                       "flat rendering mode everywhere with this flatness p_f "
                                       "(0: ordinary compositing, 1: the top priority always "
                                       "shows)")
                        .atLeast(0)
                        .atMost(1);
  spec.defaultValue.reset();
  spec.defaultNote = "none: the flatness rules decide per sample";
  return spec;
}

}  // namespace

const std::vector<OptionSpec>& semanticOptions() {
  static const std::vector<OptionSpec> options{
      OptionSpec::text("rules",
                       "fuzzy rule base: a .rules file, a preset (default, example, fig6-cube, "
                       "tooth-focus-context; README, semantic) or the rule text itself; "
                       "default: default")
          .validatedBy([](const OptionValue& value) {
            const std::string& text = std::get<std::string>(value);
            // The sphere files too: every error before any GL work.
            if (!text.empty()) buildSphereAtlas(loadRulesPreset(text), 2);
          }),
      flatnessOption(),
      OptionSpec::text("cursor",
                       "the 3D cursor X,Y,Z in voxel coordinates (cursor_distance); default the "
                       "volume's centre")
          .holdsNumbers(3),
      OptionSpec::text("cursor-pixel",
                       "the cursor's pixel X,Y, top-left origin (image_distance); default where "
                       "the 3D cursor projects")
          .holdsNumbers(2),
      OptionSpec::text("plane",
                       "the plane PX,PY,PZ,NX,NY,NZ: a point in voxel coordinates and a normal "
                       "(plane_distance); default through the centre, normal along z")
          .holdsNumbers(6)
          .validatedBy([](const OptionValue& value) {
            const auto v = parseNumberList(std::get<std::string>(value), 6);
            if (v && (*v)[3] == 0 && (*v)[4] == 0 && (*v)[5] == 0) {
              throwInputError("--plane", "the normal must not be 0,0,0");
            }
          }),
      OptionSpec::flag("plane-show", "draw the data on the plane (grey, opaque, on top)"),
      OptionSpec::number("time", 0.0, "the time source's value").atLeast(0).atMost(1),
  };
  return options;
}

RuleBase loadSemanticRules(const OptionReader& options) {
  const std::string& text = options.text("rules");
  return loadRulesPreset(text.empty() ? "default" : text);
}

ValueRange semanticDataDomain(const OptionReader& options, ValueRange range) {
  const std::string& rules = options.text("rules");
  if (!rules.empty() && rules != "default") return range;
  const DerivedDefaults& derived = options.derived();
  return classificationDomain(float(derived.iso), float(defaultClassificationTop(derived)), range);
}

SemanticInteraction resolveSemanticInteraction(const OptionReader& options, glm::ivec3 dims,
                                               const View& view) {
  SemanticInteraction interaction;
  const glm::dvec3 centre = (glm::dvec3(dims) - 1.0) * 0.5;
  interaction.cursorVoxel = centre;
  if (options.given("cursor") && !options.text("cursor").empty()) {
    const auto v = *parseNumberList(options.text("cursor"), 3);
    interaction.cursorVoxel = {v[0], v[1], v[2]};
  }
  if (options.given("cursor-pixel") && !options.text("cursor-pixel").empty()) {
    const auto v = *parseNumberList(options.text("cursor-pixel"), 2);
    interaction.cursorPixel = {v[0], v[1]};
  } else {
    const glm::dvec4 clip = view.clipFromVoxel() * glm::dvec4(interaction.cursorVoxel, 1.0);
    const glm::dvec2 ndc = glm::dvec2(clip) / clip.w;
    const glm::dvec2 size(view.viewport);
    interaction.cursorPixel = {(ndc.x + 1.0) * 0.5 * size.x - 0.5,
                               (1.0 - ndc.y) * 0.5 * size.y - 0.5};
  }
  interaction.planePointVoxel = centre;
  if (options.given("plane") && !options.text("plane").empty()) {
    const auto v = *parseNumberList(options.text("plane"), 6);
    const glm::dvec3 normal(v[3], v[4], v[5]);
    if (!(glm::length(normal) > 0)) throwInputError("--plane", "the normal must not be 0,0,0");
    interaction.planePointVoxel = {v[0], v[1], v[2]};
    interaction.planeNormal = glm::normalize(normal);
  }
  interaction.planeShow = options.enabled("plane-show");
  if (options.given("flatness")) interaction.flatness = options.number("flatness");
  interaction.time = options.number("time");
  return interaction;
}

std::vector<int> styleLayerOrder(const RuleBase& rules) {
  std::vector<int> order(rules.styles.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return rules.styles[std::size_t(a)].priority < rules.styles[std::size_t(b)].priority;
  });
  return order;
}

bool usesFlatMode(const RuleBase& rules, const SemanticInteraction& interaction) {
  if (interaction.flatness) return true;
  return std::any_of(rules.rules.begin(), rules.rules.end(),
                     [](const Rule& rule) { return rule.flatness; });
}

}  // namespace vsil
