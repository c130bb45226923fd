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

namespace {
TechniqueInfo composedBy(TechniqueInfo info, Composition composition) {
  info.composition = composition;
  return info;
}
}  // namespace

const std::vector<TechniqueInfo>& techniqueTable() {
  // How each technique's slabs combine (core/composition.h): the silhouette pair (first contour
  // value, state; depths travel with it) and the MIP family's depth records reduce exactly;
  // front-to-back "over" of premultiplied RGBA in RGBA32F is not associative in float and early
  // ray termination reads the accumulated alpha, so those frames relay the accumulated targets
  // from slab to slab in depth order (the same float operations in the same order); demip's
  // second sweep needs the whole ray's maximum, so it relays too (each sweep in turn, the first
  // sweep's maxima shared before the second). lmip relays its record as well: its run summary
  // reduces exactly (composition.h LocalMaxReduce, proven in composition_test.cpp), but the
  // relay continues the very records of lmip_slice.frag with no second formula to keep in step,
  // and costs the same sends as an ordered reduce.
  static const std::vector<TechniqueInfo> table{
      // clang-format off
      composedBy(silhouetteTechniqueInfo(), Composition::PairReduce),
      composedBy(rightAngleTechniqueInfo(), Composition::Relay),
      composedBy(firstHitTechniqueInfo(), Composition::Relay),
      composedBy(illustrateTechniqueInfo(), Composition::Relay),
      composedBy(mipTechniqueInfo(), Composition::MaxReduce),
      composedBy(demipTechniqueInfo(), Composition::Relay),
      composedBy(lmipTechniqueInfo(), Composition::Relay),
      composedBy(semanticTechniqueInfo(), Composition::Relay),
      // clang-format on
  };
  return table;
}

void requireSplittable(const TechniqueInfo& info, int ranks) {
  if (ranks <= 1) return;
  // Wired into the frame loop so far: the max reduce (mip), the silhouette pair and the relay of
  // the techniques whose samples read no voxel beyond their own bricks (rightangle, firsthit,
  // demip, lmip; the last passes that shade at a pixel's own point relay too, technique.h
  // relayScreenPass), and the compositing ones (illustrate, semantic: gradients and the halo
  // field from ghost layers with the whole volume's largest gradient agreed, early ray
  // termination's marks relayed with the colour; mark_dead.frag SLAB_OWNED_MARKS).
  if (info.composition == Composition::MaxReduce) return;
  if (info.composition == Composition::PairReduce) return;
  if (info.composition == Composition::Relay) return;
  throw UnavailableError(
      "--technique " + info.name + ": rendering across " + std::to_string(ranks) +
      " MPI ranks is not available yet (its combine rule, " + compositionName(info.composition) +
      ", is stated but the slab renderer is not wired in); run one rank");
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
    case SlicingPipeline::Paper:
      return "paper";
    case SlicingPipeline::Tiles:
      return "tiles";
    case SlicingPipeline::Fast:
      break;
  }
  return "fast";
}

OptionSpec pipelineOption(SlicingPipeline defaultPipeline) {
  OptionSpec spec = OptionSpec::choice(
      "pipeline", pipelineName(defaultPipeline), {"fast", "paper", "tiles"},
      "fast (passes per slice, skipping empty space and finished pixels), paper (the paper's "
      "passes per slice over every pixel of each slice polygon) or tiles (one compute dispatch "
      "marching screen tiles through the slices); the same pixels (illustrate: the same samples, "
      "colours equal to float rounding)");
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

bool TechniqueInfo::needsOneTextureWith(const OptionValues& given) const {
  return needsOneTexture && needsOneTexture(OptionReader(options, given, {}));
}

OptionValues optionsForSlab(const TechniqueInfo& info, OptionValues given) {
  if (info.option("pipeline") && (info.slabRunsFastPipeline || !given.contains("pipeline"))) {
    given["pipeline"] = std::string(pipelineName(SlicingPipeline::Fast));
  }
  return given;
}

bool TechniqueInfo::needsOneTextureInSlab(OptionValues given) const {
  return needsOneTextureWith(optionsForSlab(*this, std::move(given)));
}

SlicingPipeline pipelineOf(const OptionReader& options) {
  const std::string& name = options.text("pipeline");
  if (name == "paper") return SlicingPipeline::Paper;
  if (name == "tiles") return SlicingPipeline::Tiles;
  return SlicingPipeline::Fast;
}

}  // namespace vsil
