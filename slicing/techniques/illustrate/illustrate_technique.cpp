#include "slicing/techniques/illustrate/illustrate_technique.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>

#include "slicing/illustration_options.h"
#include "slicing/texture_units.h"

namespace vsil {

namespace {

const std::vector<OptionSpec>& illustrateOptions() {
  static const std::vector<OptionSpec> options{
      effectsOption(),
      parameterOption(),
      styleOption(),
      transferFunctionOption(),
      colorOption(),
      sketchColorOption(),
      lightOption(),
      OptionSpec::choice("halo-mode", "field", {"field", "exact"},
                         "halo: field (a halo field built once per volume, one fetch per sample; "
                         "works on bricked volumes) or exact (8 taps per sample in the slice "
                         "plane; needs one texture)"),
      pipelineOption(kIllustrateDefaultPipeline)};
  return options;
}

HaloMode haloModeFromOptions(const OptionReader& options) {
  return options.text("halo-mode") == "exact" ? HaloMode::Exact : HaloMode::Field;
}

std::string upper(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return char(std::toupper(c)); });
  return text;
}

// How a source of illustration values names them in a warning: the flags, or a style file.
struct ValueNames {
  std::string color, sketchColor, parameter;
};

// What of `set` changes nothing in `frame`: a colour or the power opacity's k_os, k_oe beside a
// transfer function (it gives both), an effect's parameters or colour with that effect off.
void addIgnored(const IllustrationStyle& set, const ValueNames& names, const Illustration& frame,
                std::vector<std::string>& ignored) {
  const bool transferFunction = frame.transferFunction.has_value();
  if (set.color && transferFunction) {
    ignored.push_back(names.color + ": the transfer function gives the samples' colour; ignored");
  }
  if (set.sketchColor && !frame.effects.has(Effect::Sketch)) {
    ignored.push_back(names.sketchColor + ": the sketch effect is off; ignored");
  }
  for (const auto& [name, value] : set.parameters) {
    const ParameterSpec& spec = *findParameter(name);
    if (spec.effect && !frame.effects.has(*spec.effect)) {
      ignored.push_back(names.parameter + name + ": the " + effectName(*spec.effect) +
                        " effect is off; ignored");
    } else if (transferFunction && (name == "k_os" || name == "k_oe")) {
      ignored.push_back(names.parameter + name +
                        ": the transfer function gives the opacity (k_os, k_oe shape the power "
                        "opacity without one); ignored");
    }
  }
}

// TechniqueInfo::ignoredOptions: the flags' values, and those of a style the user wrote (a
// file or inline JSON; a preset carries values for effects one may turn off), that change
// nothing; --halo-mode with the halo effect off.
std::vector<std::string> ignoredIllustrateOptions(const OptionReader& options) {
  const Illustration frame = illustrationFromOptions(illustrateOptions(), options);
  std::vector<std::string> ignored;
  addIgnored(styleFromOptions(illustrateOptions(), options),
             {"--color", "--sketch-color", "--param "}, frame, ignored);
  if (options.given("halo-mode") && !frame.effects.has(Effect::Halo)) {
    ignored.push_back("--halo-mode: the halo effect is off; ignored");
  }
  const std::string& style = options.text("style");
  if (options.given("style") && (isInlineSource(style) || isStyleFile(style))) {
    const std::string where =
        "--style " + (isInlineSource(style) ? std::string("(inline)") : style);
    addIgnored(loadStyle(style),
               {where + ": color", where + ": sketch_color", where + ": parameters: "}, frame,
               ignored);
  }
  return ignored;
}

// The rotation taking eye-space directions into world (= the gradients' physical) axes.
glm::mat3 worldFromEye(const View& view) {
  return glm::mat3(glm::transpose(glm::dmat3(view.eyeFromWorld)));
}

}  // namespace

TechniqueInfo illustrateTechniqueInfo() {
  TechniqueInfo info{
      "illustrate",
      "Ebert–Rheingans volume illustration: front-to-back compositing with "
      "boundary, silhouette, fading, sketch, distance, halo and tone effects",
      illustrateOptions(), FrameOutputs{.state = false, .color = true, .depth = false},
      [] { return std::make_unique<IllustrateTechnique>(); },
      /*usesGradients=*/true,
      /*checkValues=*/{},
      // The exact halo's taps reach farther than a brick's overlap (the field needs none).
      /*needsOneTexture=*/
      [](const OptionReader& options) {
        return tilesNeedOneTexture(options) ||
               (haloModeFromOptions(options) == HaloMode::Exact &&
                illustrationFromOptions(illustrateOptions(), options).effects.has(Effect::Halo));
      }};
  info.ignoredOptions = ignoredIllustrateOptions;
  info.samplesOffPlanes = true;      // aligned to the box entry (compositing.h)
  info.slabRunsFastPipeline = true;  // slabs relay the slice pass's colour and marks
  // The gradients (as semantic's), and with halos the halo field at an owned brick's texels,
  // which reads up to haloFieldReachVoxels(k_hr) further (halo_mask.h), plus the brick's apron
  // and padding: 4, as the fixed width for the largest k_hr (32: 38 voxels) had it.
  // HaloMaskTexture::update checks, refusing in one line where a layer falls short.
  info.slabGhostVoxels = [](const OptionReader& options, const View&, glm::ivec3) {
    const Illustration illustration = illustrationFromOptions(illustrateOptions(), options);
    if (!illustration.effects.has(Effect::Halo)) return kGradientGhostVoxels;
    return haloFieldReachVoxels(illustration["k_hr"]) + 4;
  };
  return info;
}

std::vector<std::string> illustrateDefines(const Illustration& illustration, HaloMode haloMode) {
  std::vector<std::string> defines;
  for (const auto& name : illustration.effects.names()) defines.push_back(upper(name));
  if (illustration.effects.has(Effect::Halo)) {
    if (haloMode == HaloMode::Field) {
      defines.push_back("HALO_FIELD");
      defines.push_back("HALO_FIELD_SCALE " + std::to_string(int(kHaloFieldScale)) + ".0");
    } else {
      defines.push_back("HALO_TAPS " + std::to_string(kHaloTaps));
    }
  }
  if (illustration.transferFunction) defines.emplace_back("TRANSFER_TABLE");
  defines.push_back(lightCountDefine(illustration));
  return defines;
}

std::vector<HaloTap> haloTaps(double radiusVoxels) {
  std::vector<HaloTap> taps;
  const double diagonal = std::sqrt(0.5);
  for (int k = 0; k < 4; ++k) {
    const glm::dvec2 axis = k == 0   ? glm::dvec2(1, 0)
                            : k == 1 ? glm::dvec2(0, 1)
                            : k == 2 ? glm::dvec2(-1, 0)
                                     : glm::dvec2(0, -1);
    taps.push_back({axis, 0.5 * radiusVoxels, 0});
    const glm::dvec2 corner(k == 0 || k == 3 ? diagonal : -diagonal, k < 2 ? diagonal : -diagonal);
    taps.push_back({corner, radiusVoxels, 0});
  }
  double sum = 0;
  for (auto& tap : taps) sum += tap.weight = 1.0 / (tap.distanceVoxels * tap.distanceVoxels);
  for (auto& tap : taps) tap.weight /= sum;
  return taps;
}

ResolvedOptions IllustrateTechnique::resolve(const FrameContext& frame) {
  illustration_ = illustrationFromOptions(illustrateOptions(), *frame.options);
  haloMode_ = haloModeFromOptions(*frame.options);
  table_.clear();
  if (illustration_.transferFunction) {
    table_ =
        illustration_.transferFunction->table(frame.valueRange, TransferFunctionTexture::kEntries);
  }
  if (illustration_.effects.has(Effect::Halo)) {
    // Here, not in beginFrame: the empty-space skipping asks for the mask's bricks before it.
    if (haloMode_ == HaloMode::Exact) {
      requireOneBrick(frame, "illustrate's exact halo (--halo-mode exact)",
                      "use --halo-mode field, leave out the halo effect, or give a larger "
                      "--max-texture-mib");
    }
    const double radius = illustration_["k_hr"];
    const double pushExponent = haloMode_ == HaloMode::Field ? illustration_["k_hpe"] : 0.0;
    std::vector<double> key{double(frame.volumeGeneration),
                            radius,
                            haloMode_ == HaloMode::Field ? 1.0 : 0.0,
                            pushExponent,
                            illustration_.transferFunction ? 1.0 : 0.0,
                            illustration_["k_os"] > 0 ? 1.0 : 0.0,
                            double(powerOpacityDomain(illustration_, frame.valueRange).min)};
    for (const auto& entry : table_) key.push_back(entry.a > 0 ? 1.0 : 0.0);
    haloMask_.update(key, *frame.volume, frame.spacing, haloMode_,
                     visibleValues(illustration_, table_, frame.valueRange),
                     transparentValues(illustration_, table_, frame.valueRange), radius,
                     pushExponent, frame.slab);
  }
  ResolvedOptions resolved;
  resolved.background = illustration_.background;
  resolved.details["illustration"] = illustration_.toJson();
  return resolved;
}

std::function<bool(float)> visibleValues(const Illustration& illustration,
                                         const std::vector<glm::vec4>& table, ValueRange range) {
  if (illustration.transferFunction) {
    return [&table, range](float value) {
      return TransferFunctionTexture::opaqueSomewhere(table, range, value, value);
    };
  }
  const bool opaque = illustration["k_os"] > 0;
  const float from = powerOpacityDomain(illustration, range).min;
  return [opaque, from](float value) { return opaque && value > from; };
}

std::function<bool(float, float)> transparentValues(const Illustration& illustration,
                                                    const std::vector<glm::vec4>& table,
                                                    ValueRange range) {
  if (illustration.transferFunction) {
    return [&table, range](float lo, float hi) {
      return !TransferFunctionTexture::opaqueSomewhere(table, range, lo, hi);
    };
  }
  const bool opaque = illustration["k_os"] > 0;
  const float from = powerOpacityDomain(illustration, range).min;
  return [opaque, from](float, float hi) { return !opaque || hi <= from; };
}

ValueRange powerOpacityDomain(const Illustration& illustration, ValueRange range) {
  return classificationDomain(illustration.powerOpacityFrom, illustration.powerOpacityTo, range);
}

float transparentBelow(const Illustration& illustration, const std::vector<glm::vec4>& table,
                       ValueRange range) {
  if (!illustration.transferFunction) return powerOpacityDomain(illustration, range).min;
  // Entries before the first opaque one are 0: values up to the entry before it read 0 (a
  // sample just above interpolates towards the opaque entry).
  const auto first =
      std::find_if(table.begin(), table.end(), [](const glm::vec4& e) { return e.a > 0; });
  if (first == table.begin()) return -std::numeric_limits<float>::infinity();
  if (first == table.end()) return range.max;
  const double before = double(first - table.begin() - 1);
  return float(double(range.min) +
               (double(range.max) - double(range.min)) * before / double(table.size() - 1));
}

BrickOccupancy IllustrateTechnique::occupancy(const FrameContext& frame) const {
  const ValueRange range = frame.valueRange;
  if (illustration_.transferFunction) {
    return [table = table_, range](ValueRange brick) {
      return TransferFunctionTexture::opaqueSomewhere(table, range, brick.min, brick.max);
    };
  }
  // o_v = k_os·v^k_oe is above 0 exactly where v is: anywhere above where the power starts.
  const bool opaque = illustration_["k_os"] > 0;
  const float from = powerOpacityDomain(illustration_, range).min;
  return [opaque, from](ValueRange brick) { return opaque && brick.max > from; };
}

std::vector<bool> IllustrateTechnique::alsoOccupied(const FrameContext&) const {
  // Halo opacity appears where the halo mask is 1, also in bricks the transfer function leaves
  // transparent.
  if (!illustration_.effects.has(Effect::Halo) || !(illustration_["k_ho"] > 0)) return {};
  return haloMask_.bricks();
}

void IllustrateTechnique::beginFrame(const FrameContext& frame) {
  const GradientTexture& gradients = frame.gradients->texture();
  std::vector<std::string> defines = illustrateDefines(illustration_, haloMode_);
  gradients.addDefines(defines);
  const std::vector<std::string> sources{kCompositingSource, "shaders/gradients.glsl",
                                         "shaders/illustration.glsl",
                                         "techniques/illustrate/illustrate_sample.glsl"};
  const SlicingPipeline pipeline = pipelineOf(*frame.options);
  if (pipeline == SlicingPipeline::Tiles) {
    requireOneBrick(frame, "--pipeline tiles", "use --pipeline fast (the same samples)");
    defines.emplace_back("SKIP_SAMPLE return false");
    program_ = &FrontToBackCompositor::marchProgram(
        frame, sources, "techniques/illustrate/march.comp", std::move(defines));
  } else {
    defines.emplace_back(kBoxAlignedSampling);
    defines.emplace_back("SKIP_SAMPLE discard");
    program_ = &frame.programs->get(
        gl::slicePassProgram(sources, "techniques/illustrate/composite.frag", std::move(defines)));
  }
  if (illustration_.transferFunction) {
    if (!transferTexture_) transferTexture_.emplace();
    transferTexture_->upload(*illustration_.transferFunction, frame.valueRange);
    gl::bindTexture(gl::TextureUnit::TransferFunction, GL_TEXTURE_1D, transferTexture_->id());
  }
  gl::bindTexture(gl::TextureUnit::Gradient, GL_TEXTURE_3D, gradients.brickTexture(0));
  if (illustration_.effects.has(Effect::Halo)) {  // brick 0; drawSlice binds the others
    gl::bindTexture(gl::TextureUnit::Auxiliary0, GL_TEXTURE_3D, haloMask_.id());
  }
  setUniforms(frame);
  compositor_.beginFrame(frame, pipeline);
}

void IllustrateTechnique::setUniforms(const FrameContext& frame) {
  gl::Program& program = *program_;
  program.use();
  for (const auto& [name, value] : illustration_.parameters)
    program.set(name.c_str(), float(value));
  program.set("toneScale", float(1.0 / std::max(1.0, toneShadingPeak(illustration_))));
  const glm::mat3 rotation = worldFromEye(*frame.view);
  program.set("worldFromEye", rotation);
  std::vector<glm::vec3> lights;
  for (const Light& light : illustration_.lights) {
    lights.push_back(rotation * glm::vec3(light.directionEye()));
  }
  program.set("lightDirections", lights.data(), int(lights.size()));
  program.set("sketchColor", illustration_.sketchColor.rgb01());
  program.set("backgroundColor", frame.background.rgb01());
  program.set("opacityExponent", FrontToBackCompositor::opacityExponent(frame));
  program.set("transparentBelow", transparentBelow(illustration_, table_, frame.valueRange));
  const ValueRange range = frame.valueRange;
  if (illustration_.transferFunction) {
    program.set("tableCoordFromValue", TransferFunctionTexture::coordinateFromValue(range));
  } else {
    const ValueRange domain = powerOpacityDomain(illustration_, range);
    const double span = double(domain.max) - double(domain.min);
    program.set("valueMin", domain.min);
    program.set("valueScale", span > 0 ? float(1.0 / span) : 0.0f);
    program.set("sampleColor", illustration_.color.rgb01());
  }
  if (illustration_.effects.has(Effect::Halo) && haloMode_ == HaloMode::Exact) {
    // Offsets in voxels: a unit step in voxel index space along the view's x and y.
    const glm::dmat3 voxelFromEye = glm::inverse(glm::dmat3(frame.view->eyeFromVoxel));
    std::vector<glm::vec3> offsets, directions;
    std::vector<float> weights;
    for (const HaloTap& tap : haloTaps(illustration_["k_hr"])) {
      const glm::dvec3 eye(tap.offsetEye, 0.0);
      const glm::dvec3 voxel = glm::normalize(voxelFromEye * eye) * tap.distanceVoxels;
      offsets.emplace_back(voxel);
      directions.push_back(rotation * glm::vec3(-eye));
      weights.push_back(float(tap.weight));
    }
    program.set("haloOffsets", offsets.data(), int(offsets.size()));
    program.set("haloDirections", directions.data(), int(directions.size()));
    program.set("haloWeights", weights.data(), int(weights.size()));
  }
}

void IllustrateTechnique::drawSlice(const FrameContext& frame, const SliceContext& slice) {
  if (compositor_.pipeline() == SlicingPipeline::Tiles) return;  // endFrame marches
  const bool haloBricks = illustration_.effects.has(Effect::Halo) && frame.volume->brickCount() > 1;
  compositor_.drawSlice(frame, slice, *program_, haloBricks ? &haloMask_.brickTextures() : nullptr);
}

void IllustrateTechnique::endFrame(const FrameContext& frame) {
  if (compositor_.pipeline() == SlicingPipeline::Tiles) compositor_.march(frame, *program_);
}

FrameBuffers IllustrateTechnique::readBack(const FrameContext&) {
  FrameBuffers frame;
  frame.color = compositor_.readBack();
  return frame;
}

}  // namespace vsil
