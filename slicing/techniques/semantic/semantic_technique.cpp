#include "slicing/techniques/semantic/semantic_technique.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "core/clock.h"
#include "slicing/gl_state.h"
#include "slicing/hit_records.h"
#include "slicing/texture_units.h"

namespace vsil {

namespace {

// A float texture read with texelFetch (nearest, clamped), replaced whole.
void uploadFetchTexture2D(gl::TextureName& texture, GLenum internalFormat, GLenum format, int width,
                          int height, const float* data) {
  if (!texture) texture = gl::createTexture();
  VSIL_GL(glBindTexture(GL_TEXTURE_2D, texture.id()));
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  VSIL_GL(glTexImage2D(GL_TEXTURE_2D, 0, GLint(internalFormat), width, height, 0, format, GL_FLOAT,
                       data));
  VSIL_GL(glBindTexture(GL_TEXTURE_2D, 0));
}

// A table of `rows` rows of `size` entries of `channels` floats each, as texels of its segments:
// texel k of a row holds entries k and k + 1 (size − 1 texels a row), so that a lookup
// interpolating between two entries (semantic.glsl) fetches one texel, not two. llvmpipe pays
// a texel fetch mostly in its addressing, whatever the texel's width.
std::vector<float> tableSegments(const std::vector<float>& entries, int size, int rows,
                                 int channels) {
  const std::size_t width = std::size_t(channels);
  std::vector<float> segments(std::size_t(size - 1) * std::size_t(rows) * 2 * width, 0.0f);
  if (entries.size() < std::size_t(size) * std::size_t(rows) * width) return segments;  // no rows
  for (std::size_t row = 0; row < std::size_t(rows); ++row) {
    for (std::size_t k = 0; k + 1 < std::size_t(size); ++k) {
      const float* from = entries.data() + (row * std::size_t(size) + k) * width;
      float* to = segments.data() + (row * std::size_t(size - 1) + k) * 2 * width;
      std::copy(from, from + 2 * width, to);
    }
  }
  return segments;
}

std::string membershipKeyOf(const RuleBase& rules) {
  std::string key;
  for (const Attribute& attribute : rules.attributes) {
    for (const SemanticValue& value : attribute.values) key += value.function.text() + ";";
    key += "|";
  }
  return key;
}

std::string defuzzKeyOf(const RuleBase& rules) {
  std::string key;
  for (const Style& style : rules.styles) {
    for (const SemanticValue& value : style.values) key += value.function.text() + ";";
    key += "|";
  }
  for (const SemanticValue& value : rules.flatness) key += value.function.text() + ";";
  return key;
}

std::string atlasKeyOf(const RuleBase& rules) {
  std::string key;
  for (const Style& style : rules.styles) {
    key += style.spheres.builtin + "|" + style.spheres.file.string() + ";";
  }
  return key;
}

glm::mat3 semanticWorldFromEye(const View& view) {
  return glm::mat3(glm::transpose(glm::dmat3(view.eyeFromWorld)));
}

}  // namespace

TechniqueInfo semanticTechniqueInfo() {
  TechniqueInfo info{
      "semantic",
      "Rautek et al. interaction-dependent semantics: fuzzy rules (--rules) compiled to the "
      "slice shader, lit-sphere styles by priority, the flat rendering mode",
      semanticOptions(),
      FrameOutputs{.state = false, .color = true, .depth = false},
      [] { return std::make_unique<SemanticTechnique>(); },
      /*usesGradients=*/true,
      /*checkValues=*/{},
      /*needsOneTexture=*/{}};
  info.samplesOffPlanes = true;  // aligned to the box entry (compositing.h)
  info.slabGhostVoxels = [](const OptionReader&, const View&, glm::ivec3) {
    return kGradientGhostVoxels;
  };
  return info;
}

gl::ProgramSpec semanticProgram(const CompiledRules& compiled, bool flat, bool planeShow,
                                const GradientTexture& gradients) {
  const auto file = [](const char* path) { return gl::ShaderSource::file(path); };
  gl::ProgramSpec spec;
  spec.vertex = {file("shaders/common.glsl"), file("shaders/slice.vert")};
  spec.fragment = {file("shaders/common.glsl"),
                   file(kCompositingSource),
                   file("shaders/gradients.glsl"),
                   file("techniques/semantic/semantic.glsl"),
                   gl::ShaderSource::generated("rules", compiled.glsl),
                   file("techniques/semantic/semantic.frag")};
  if (flat) spec.defines.emplace_back("SEMANTIC_FLAT");
  if (planeShow) spec.defines.emplace_back("SEMANTIC_PLANE_SHOW");
  gradients.addDefines(spec.defines);
  spec.defines.emplace_back(kBoxAlignedSampling);
  return spec;
}

ResolvedOptions SemanticTechnique::resolve(const FrameContext& frame) {
  rules_ = loadSemanticRules(*frame.options);
  const auto compileStart = std::chrono::steady_clock::now();
  compiled_ = compileRules(rules_);
  const double compileMs = millisecondsSince(compileStart);
  interaction_ = resolveSemanticInteraction(*frame.options, frame.dims, *frame.view);
  flat_ = usesFlatMode(rules_, interaction_);

  // Membership rows (and what data values can show) follow the attributes' functions.
  const std::string membershipKey = membershipKeyOf(rules_);
  if (membershipKey != membershipKey_ || !membershipTexture_) {
    membership_ = buildMembershipTables(rules_);
    const std::vector<float> segments =
        tableSegments(membership_.entries, membership_.size, std::max(membership_.rows, 1), 1);
    uploadFetchTexture2D(membershipTexture_, GL_RG32F, GL_RG, membership_.size - 1,
                         std::max(membership_.rows, 1), segments.data());
    membershipKey_ = membershipKey;
  }
  visible_ = visibleDataIntervals(rules_, membership_);
  std::vector<float> visibleRow(visible_.begin(), visible_.end());
  uploadFetchTexture2D(visibleTexture_, GL_R32F, GL_RED, int(visibleRow.size()), 1,
                       visibleRow.data());
  const std::string defuzzKey = defuzzKeyOf(rules_);
  if (defuzzKey != defuzzKey_ || !defuzzTexture_) {
    const DefuzzTables tables = buildDefuzzTables(rules_);
    std::vector<float> pairs(std::size_t(tables.size) * std::size_t(std::max(tables.rows, 1)) * 2,
                             0.0f);
    for (std::size_t i = 0; i < tables.numerator.size(); ++i) {
      pairs[2 * i] = tables.numerator[i];
      pairs[2 * i + 1] = tables.denominator[i];
    }
    const std::vector<float> segments =
        tableSegments(pairs, tables.size, std::max(tables.rows, 1), 2);
    uploadFetchTexture2D(defuzzTexture_, GL_RGBA32F, GL_RGBA, tables.size - 1,
                         std::max(tables.rows, 1), segments.data());
    defuzzKey_ = defuzzKey;
  }
  const std::string atlasKey = atlasKeyOf(rules_);
  if (atlasKey != atlasKey_ || !atlasTexture_) {
    atlas_ = buildSphereAtlas(rules_);
    if (!atlasTexture_) atlasTexture_ = gl::createTexture();
    VSIL_GL(glBindTexture(GL_TEXTURE_3D, atlasTexture_.id()));
    glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    for (GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R}) {
      glTexParameteri(GL_TEXTURE_3D, wrap, GL_CLAMP_TO_EDGE);
    }
    VSIL_GL(glTexImage3D(GL_TEXTURE_3D, 0, GL_RGBA32F, atlas_->cell, atlas_->cell, atlas_->depth, 0,
                         GL_RGBA, GL_FLOAT, atlas_->texels.data()));
    VSIL_GL(glBindTexture(GL_TEXTURE_3D, 0));
    atlasKey_ = atlasKey;
  }

  const GradientTexture& gradients = frame.gradients->texture();  // built before the timing
  const int buildsBefore = frame.programs->builds();
  const auto buildStart = std::chrono::steady_clock::now();
  program_ =
      &frame.programs->get(semanticProgram(compiled_, flat_, interaction_.planeShow, gradients));
  const double buildMs = millisecondsSince(buildStart);

  ResolvedOptions resolved;
  nlohmann::json& details = resolved.details["semantic"];
  details["rules_source"] = rules_.source;
  details["rules"] = rules_.rules.size();
  details["styles"] = rules_.styles.size();
  details["flat_mode"] = flat_;
  details["rule_compile_ms"] = compileMs;
  details["generated_glsl_bytes"] = compiled_.glsl.size();
  details["program_compiled"] = frame.programs->builds() > buildsBefore;
  details["program_build_ms"] = buildMs;
  details["warnings"] = rules_.warnings;
  // The values the data source's [0, 1] spans (semanticDataDomain).
  const ValueRange domain = semanticDataDomain(*frame.options, frame.valueRange);
  details["data_domain"] = {domain.min, domain.max};
  // The interaction as used, defaults resolved (the options hold "" for those not given): the
  // values --cursor, --cursor-pixel and --plane take to replay it.
  const SemanticInteraction& i = interaction_;
  details["cursor"] = {i.cursorVoxel.x, i.cursorVoxel.y, i.cursorVoxel.z};
  details["cursor_pixel"] = {i.cursorPixel.x, i.cursorPixel.y};
  details["plane"] = {i.planePointVoxel.x, i.planePointVoxel.y, i.planePointVoxel.z,
                      i.planeNormal.x,     i.planeNormal.y,     i.planeNormal.z};
  return resolved;
}

BrickOccupancy SemanticTechnique::occupancy(const FrameContext& frame) const {
  if (interaction_.planeShow) return [](ValueRange) { return true; };
  const ValueRange range = semanticDataDomain(*frame.options, frame.valueRange);
  const double span = double(range.max) - double(range.min);
  return [visible = visible_, range, span](ValueRange brick) {
    const int last = int(visible.size());  // entries − 1
    const auto entry = [&](double value) {
      return span > 0 ? (value - double(range.min)) / span * last : 0.0;
    };
    // One interval of slack on each side for the rounding of the normalized value.
    const int first = std::clamp(int(std::floor(entry(brick.min))) - 1, 0, last - 1);
    const int end = std::clamp(int(std::ceil(entry(brick.max))) + 1, 0, last - 1);
    for (int k = first; k <= end; ++k) {
      if (visible[std::size_t(k)]) return true;
    }
    return false;
  };
}

void SemanticTechnique::beginFrame(const FrameContext& frame) {
  // resolve() uploaded the atlas through unit 0's 3D binding: the volume's again.
  gl::bindTexture(gl::TextureUnit::Volume, GL_TEXTURE_3D, frame.volume->brickTexture(0));
  gl::bindTexture(gl::TextureUnit::Gradient, GL_TEXTURE_3D,
                  frame.gradients->texture().brickTexture(0));
  gl::bindTexture(gl::TextureUnit::Auxiliary0, GL_TEXTURE_2D, membershipTexture_.id());
  gl::bindTexture(gl::TextureUnit::Auxiliary1, GL_TEXTURE_2D, defuzzTexture_.id());
  gl::bindTexture(gl::TextureUnit::Auxiliary2, GL_TEXTURE_3D, atlasTexture_.id());
  gl::bindTexture(gl::TextureUnit::Auxiliary3, GL_TEXTURE_2D, visibleTexture_.id());
  setUniforms(frame);
  if (!flat_) {
    compositor_.beginFrame(frame);
    return;
  }
  const glm::ivec2 size = frame.view->viewport;
  if (!flatTargets_ || flatTargets_->color.size() != size) {
    flatTargets_.reset();
    gl::RenderTarget color(size, GL_RGBA32F, /*withDepthStencil=*/true);
    gl::RenderTarget priority(size, GL_R32F);
    const GLuint depth = color.depthStencil();
    flatTargets_.emplace(
        FlatTargets{std::move(color), std::move(priority), gl::EmptyFramebuffer(size, depth)});
  }
  gl::Capability noScissor(GL_SCISSOR_TEST, false);
  const GLfloat transparent[4] = {0, 0, 0, 0};
  const GLfloat lowest[4] = {-1e30f, 0, 0, 0};
  flatTargets_->priority.bindForDrawing();
  VSIL_GL(glClearBufferfv(GL_COLOR, 0, lowest));
  flatTargets_->color.bindForDrawing();
  VSIL_GL(glClearBufferfv(GL_COLOR, 0, transparent));
  frame.emptySpace->writeEntryDepth(glm::mat4(frame.view->clipFromVoxel()));
  gl::bindImage(gl::ImageUnit::Record, flatTargets_->color);
  gl::bindImage(gl::ImageUnit::Auxiliary0, flatTargets_->priority);
}

void SemanticTechnique::setUniforms(const FrameContext& frame) {
  gl::Program& program = *program_;
  program.use();
  const ValueRange range = semanticDataDomain(*frame.options, frame.valueRange);
  const double span = double(range.max) - double(range.min);
  program.set("valueMin", range.min);
  program.set("valueScale", span > 0 ? float(1.0 / span) : 0.0f);
  const glm::mat3 worldFromEye = semanticWorldFromEye(*frame.view);
  program.set("worldFromEye", worldFromEye);
  program.set("eyeFromWorld", glm::transpose(worldFromEye));
  program.set("opacityExponent", FrontToBackCompositor::opacityExponent(frame));

  const std::vector<int> order = styleLayerOrder(rules_);
  std::vector<float> priorities, first, span1;
  float top = -1e30f;
  for (std::size_t s = 0; s < rules_.styles.size(); ++s) {
    priorities.push_back(float(rules_.styles[s].priority));
    top = std::max(top, priorities.back());
    first.push_back(float(atlas_->firstLayer[s]));
    span1.push_back(float(atlas_->sphereCount[s] - 1));
  }
  program.set("styleOrder", order.data(), int(order.size()));
  program.set("stylePriority", priorities.data(), int(priorities.size()));
  program.set("sphereFirst", first.data(), int(first.size()));
  program.set("sphereSpan", span1.data(), int(span1.size()));
  program.set("atlasDepth", float(atlas_->depth));
  program.set("topPriority", interaction_.planeShow ? top + 1.0f : top);

  const glm::dvec3 spacing = frame.spacing;
  program.set("voxelSpacing", glm::vec3(spacing));
  program.set("inverseDiagonal", float(1.0 / glm::length(glm::dvec3(frame.dims) * spacing)));
  program.set("cursorPhysical", glm::vec3(interaction_.cursorVoxel * spacing));
  program.set("planePointPhysical", glm::vec3(interaction_.planePointVoxel * spacing));
  program.set("planeNormal", glm::vec3(interaction_.planeNormal));
  program.set("planeHalfThickness", float(0.5 * std::min({spacing.x, spacing.y, spacing.z})));
  const glm::dvec2 size(frame.view->viewport);
  program.set("cursorWindow", glm::vec2(float(interaction_.cursorPixel.x + 0.5),
                                        float(size.y - interaction_.cursorPixel.y - 0.5)));
  program.set("inverseImageDiagonal", float(1.0 / glm::length(size)));
  program.set("timeValue", float(interaction_.time));
  program.set("globalFlatness", interaction_.flatness ? float(*interaction_.flatness) : -1.0f);
  program.set("terminationOpacity",
              frame.settings->earlyRayTermination ? kTerminationOpacity : 2.0f);
}

void SemanticTechnique::drawSlice(const FrameContext& frame, const SliceContext& slice) {
  if (!flat_) {
    compositor_.drawSlice(frame, slice, *program_);
    return;
  }
  if (slice.vertexCount == 0) return;
  flatTargets_->draw.bindForDrawing();
  {
    gl::DepthTest skipEmptyAndDead(GL_GREATER, /*write=*/false);
    program_->use();
    drawSlicePolygon(frame, slice);
  }
  // The next slice reads what this one stored.
  VSIL_GL(glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT));
  if (slice.index % kMarkDeadInterval == kMarkDeadInterval - 1) {
    // Past the exit of occupied space only (no opacity reaches 2): an opaque pixel may still
    // enter a higher priority.
    VSIL_GL(glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT));
    markDeadPixels(frame, slice, flatTargets_->draw, flatTargets_->color, DeadRule::Opacity, 2.0f);
  }
}

FrameBuffers SemanticTechnique::readBack(const FrameContext&) {
  FrameBuffers frame;
  if (!flat_) {
    frame.color = compositor_.readBack();
    return frame;
  }
  VSIL_GL(glMemoryBarrier(GL_ALL_BARRIER_BITS));
  frame.color = readTargetFlipped(flatTargets_->color, 4);
  return frame;
}

}  // namespace vsil
