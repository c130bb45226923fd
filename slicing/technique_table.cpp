#include "slicing/technique_table.h"

#include <algorithm>

#include "core/error.h"
#include "slicing/techniques/firsthit/firsthit_technique.h"
#include "slicing/techniques/illustrate/illustrate_technique.h"
#include "slicing/techniques/mip/lmip_technique.h"
#include "slicing/techniques/mip/mip_technique.h"
#include "slicing/techniques/rightangle/rightangle_technique.h"
#include "slicing/techniques/semantic/semantic_technique.h"
#include "slicing/techniques/silhouette/silhouette_technique.h"

namespace vsil {

const std::vector<TechniqueInfo>& techniqueTable() {
  static const std::vector<TechniqueInfo> table{
      // clang-format off
      silhouetteTechniqueInfo(),
      rightAngleTechniqueInfo(),
      firstHitTechniqueInfo(),
      illustrateTechniqueInfo(),
      mipTechniqueInfo(),
      demipTechniqueInfo(),
      lmipTechniqueInfo(),
      semanticTechniqueInfo(),
      // clang-format on
  };
  return table;
}

const OptionSpec* TechniqueInfo::option(const std::string& optionName) const {
  const auto it = std::find_if(options.begin(), options.end(),
                               [&](const OptionSpec& spec) { return spec.name == optionName; });
  return it == options.end() ? nullptr : &*it;
}

std::vector<std::string> techniqueNames() {
  std::vector<std::string> names;
  for (const auto& info : techniqueTable()) names.push_back(info.name);
  return names;
}

const TechniqueInfo& findTechnique(const std::string& name) {
  for (const auto& info : techniqueTable()) {
    if (info.name == name) return info;
  }
  std::string known;
  for (const auto& other : techniqueNames()) known += (known.empty() ? "" : ", ") + other;
  throw InputError("--technique: unknown technique '" + name + "' (known: " + known + ")");
}

OptionSpec isoOption() {
  OptionSpec spec = OptionSpec::number("iso", 0, "iso value in the data's own units");
  spec.defaultValue.reset();
  spec.derived = OptionSpec::Derived::VolumeIso;
  spec.defaultNote = "from the volume (vsil info)";
  return spec;
}

const char* pipelineName(SlicingPipeline pipeline) {
  switch (pipeline) {
    case SlicingPipeline::Paper: return "paper";
    case SlicingPipeline::Tiles: return "tiles";
    case SlicingPipeline::Fast: break;
  }
  return "fast";
}

OptionSpec pipelineOption(SlicingPipeline defaultPipeline) {
  OptionSpec spec = OptionSpec::choice(
      "pipeline", pipelineName(defaultPipeline), {"fast", "paper", "tiles"},
      "fast (passes per slice, skipping empty space and finished pixels), paper (the paper's "
      "passes per slice over every pixel of each slice polygon) or tiles (one compute dispatch "
      "marching screen tiles through the slices); the same pixels");
  if (defaultPipeline == SlicingPipeline::Tiles) {
    spec.defaultNote = "fast where the volume takes several bricks: tiles needs one texture";
  }
  return spec;
}

bool tilesNeedOneTexture(const OptionReader& options) {
  return options.given("pipeline") && pipelineOf(options) == SlicingPipeline::Tiles;
}

OptionValues optionsForBricks(const TechniqueInfo& info, OptionValues given, std::size_t bricks) {
  const OptionSpec* pipeline = info.option("pipeline");
  if (bricks > 1 && pipeline && !given.contains("pipeline") &&
      std::get<std::string>(*pipeline->defaultValue) == pipelineName(SlicingPipeline::Tiles)) {
    given["pipeline"] = std::string(pipelineName(SlicingPipeline::Fast));
  }
  return given;
}

bool needsOneTexture(const std::string& technique, const OptionValues& given) {
  const TechniqueInfo& info = findTechnique(technique);
  return info.needsOneTexture && info.needsOneTexture(OptionReader(info.options, given, {}));
}

SlicingPipeline pipelineOf(const OptionReader& options) {
  const std::string& name = options.text("pipeline");
  if (name == "paper") return SlicingPipeline::Paper;
  if (name == "tiles") return SlicingPipeline::Tiles;
  return SlicingPipeline::Fast;
}

}  // namespace vsil
