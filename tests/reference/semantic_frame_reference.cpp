#include "semantic_frame_reference.h"

#include <algorithm>
#include <cmath>

#include "semantic_reference.h"
#include "slice_sampler.h"
#include "slicing/gradient_texture.h"
#include "slicing/technique_table.h"
#include "slicing/techniques/semantic/rule_compiler.h"
#include "slicing/techniques/semantic/semantic_scene.h"
#include "slicing/techniques/semantic/sphere_atlas.h"

namespace vsil::reference {
namespace {

glm::vec4 semanticSampleAtlas(const SphereAtlas& atlas, glm::vec3 coord) {
  const LinearTaps tx = linearTaps(coord.x, atlas.cell), ty = linearTaps(coord.y, atlas.cell),
                   tz = linearTaps(coord.z, atlas.depth);
  glm::vec4 result(0.0f);
  for (int dz = 0; dz < 2; ++dz) {
    for (int dy = 0; dy < 2; ++dy) {
      for (int dx = 0; dx < 2; ++dx) {
        const float w = (dx ? tx.f : 1 - tx.f) * (dy ? ty.f : 1 - ty.f) * (dz ? tz.f : 1 - tz.f);
        result += w * atlas.at(dx ? tx.i1 : tx.i0, dy ? ty.i1 : ty.i0, dz ? tz.i1 : tz.i0);
      }
    }
  }
  return result;
}

// A rule's degree from the membership tables (the tree walked: and = min, or = max, not = 1 − x).
float tableDegree(const RuleBase& rules, const Condition& condition,
                  const MembershipTables& membership, const AttributeInputs& inputs) {
  switch (condition.op) {
    case Condition::Op::Is: {
      const Attribute& attribute = rules.attributes[std::size_t(condition.attribute)];
      return membership.at(membership.firstRow[std::size_t(condition.attribute)] + condition.value,
                           float(inputs[std::size_t(attribute.source)]));
    }
    case Condition::Op::Not:
      return 1.0f - tableDegree(rules, condition.operands.front(), membership, inputs);
    case Condition::Op::And: {
      float degree = 1.0f;
      for (const auto& operand : condition.operands) {
        degree = std::min(degree, tableDegree(rules, operand, membership, inputs));
      }
      return degree;
    }
    case Condition::Op::Or: {
      float degree = 0.0f;
      for (const auto& operand : condition.operands) {
        degree = std::max(degree, tableDegree(rules, operand, membership, inputs));
      }
      return degree;
    }
  }
  return 0.0f;
}

// (N, D) of a row at a degree, the two entries around it mixed in float.
glm::vec2 defuzzAt(const DefuzzTables& tables, int row, float degree) {
  const float t = std::clamp(degree, 0.0f, 1.0f) * float(tables.size - 1);
  const int k = std::min(int(t), tables.size - 2);
  const float f = t - float(k);
  const std::size_t at = std::size_t(row) * std::size_t(tables.size) + std::size_t(k);
  return glm::vec2(tables.numerator[at], tables.denominator[at]) * (1.0f - f) +
         glm::vec2(tables.numerator[at + 1], tables.denominator[at + 1]) * f;
}

}  // namespace

ReferenceFrame renderSemantic(const Volume& volume, const RenderSettings& settings, float) {
  const ReferenceSetup setup = setUpReference(volume, settings);
  const View& view = setup.view;
  const RuleBase rules = loadSemanticRules(setup.options);
  const SemanticInteraction interaction =
      resolveSemanticInteraction(setup.options, volume.dims, view);
  const bool flat = usesFlatMode(rules, interaction);
  const MembershipTables membership = buildMembershipTables(rules);
  const std::vector<std::uint8_t> visible = visibleDataIntervals(rules, membership);
  const DefuzzTables defuzz = buildDefuzzTables(rules);
  const SphereAtlas atlas = buildSphereAtlas(rules);
  const std::vector<int> order = styleLayerOrder(rules);
  float topPriority = -1e30f;
  for (const Style& style : rules.styles)
    topPriority = std::max(topPriority, float(style.priority));
  if (interaction.planeShow) topPriority += 1.0f;

  const ValueRange range = semanticDataDomain(setup.options, valueRange(volume));
  const double span = double(range.max) - double(range.min);
  const float valueScale = span > 0 ? float(1.0 / span) : 0.0f;
  const SliceSampler sampler(volume, view);
  const std::vector<float> texels = textureTexels(volume);
  const GradientTexels gradients =
      computeGradientTexels(texels.data(), volume.dims, volume.spacing, /*withValues=*/false);
  const glm::mat3 worldFromEye(glm::transpose(glm::dmat3(view.eyeFromWorld)));
  const glm::mat3 eyeFromWorld = glm::transpose(worldFromEye);
  const glm::vec3 spacing(volume.spacing);
  const float inverseDiagonal = float(1.0 / glm::length(glm::dvec3(volume.dims) * volume.spacing));
  const glm::vec3 cursorPhysical(interaction.cursorVoxel * volume.spacing);
  const glm::vec3 planePoint(interaction.planePointVoxel * volume.spacing);
  const glm::vec3 planeNormal(interaction.planeNormal);
  const float planeHalfThickness =
      float(0.5 * std::min({volume.spacing.x, volume.spacing.y, volume.spacing.z}));
  const glm::dvec2 size(settings.size);
  const glm::vec2 cursorWindow(float(interaction.cursorPixel.x + 0.5),
                               float(size.y - interaction.cursorPixel.y - 0.5));
  const float inverseImageDiagonal = float(1.0 / glm::length(size));
  const float exponent = float(setup.plan.stepVoxels);

  // Samples on each pixel's ray, aligned to its entry into the box (BOX_ALIGNED_SAMPLING).
  const PixelRays rays = pixelRays(view, setup.plan);
  ReferenceFrame result = emptyReferenceFrame(setup, settings.size, /*color=*/true);
  const int styleCount = int(rules.styles.size());
  std::vector<float> weight(static_cast<std::size_t>(styleCount), 0.0f);
  std::vector<float> styleValue(static_cast<std::size_t>(styleCount), 0.0f);
  for (int y = 0; y < settings.size.y; ++y) {
    for (int x = 0; x < settings.size.x; ++x) {
      glm::vec4 dst(0.0f);
      float top = -1e30f;
      const SliceSampler::BoxAlignedRay ray = sampler.boxAlignedRay(x, y, rays);
      bool ambiguous = ray.phaseAmbiguous;
      const glm::vec2 fragCoord(float(x) + 0.5f, float(settings.size.y - 1 - y) + 0.5f);
      for (std::size_t k = 0; k < setup.plan.slices.size(); ++k) {
        const Slice& slice = setup.plan.slices[k];
        if (slice.polygonVoxel.empty()) continue;
        const glm::vec3 voxel = SliceSampler::boxAlignedVoxel(ray, int(k));
        if (!sampler.insideVolume(voxel)) continue;
        const float value = sampler.sample(voxel);
        const float data = std::clamp((value - range.min) * valueScale, 0.0f, 1.0f);
        const glm::vec3 physical = voxel * spacing;
        const bool onPlane =
            interaction.planeShow &&
            std::abs(glm::dot(physical - planePoint, planeNormal)) <= planeHalfThickness;
        const int intervals = int(visible.size());
        const int interval = std::min(int(data * float(intervals)), intervals - 1);
        if (!onPlane && !visible[std::size_t(interval)]) continue;

        const SplitGradient g = splitGradient(sampleGradientTexels(gradients, voxel));
        const glm::vec3 direction = g.direction;
        AttributeInputs inputs{};
        inputs[int(AttributeSource::Data)] = data;
        inputs[int(AttributeSource::Gradient)] = g.magnitude;
        inputs[int(AttributeSource::CursorDistance)] =
            glm::length(physical - cursorPhysical) * inverseDiagonal;
        inputs[int(AttributeSource::PlaneDistance)] =
            std::abs(glm::dot(physical - planePoint, planeNormal)) * inverseDiagonal;
        inputs[int(AttributeSource::ImageDistance)] =
            glm::length(fragCoord - cursorWindow) * inverseImageDiagonal;
        const glm::vec3 toViewer =
            view.orthographic ? glm::vec3(0, 0, 1)
                              : -glm::normalize(sampler.eyePoint(x, y, float(slice.eyeDistance)));
        inputs[int(AttributeSource::ViewAngle)] =
            std::acos(std::clamp(glm::dot(direction, -(worldFromEye * toViewer)), -1.0f, 1.0f)) /
            3.14159265358979f;
        inputs[int(AttributeSource::Time)] = float(interaction.time);

        // Rules, then per consequent Σ (N, D) in file order and the largest degree.
        std::vector<float> degrees;
        for (const Rule& rule : rules.rules) {
          degrees.push_back(tableDegree(rules, rule.antecedent, membership, inputs));
        }
        const auto consequent = [&](bool flatness, int style) {
          glm::vec2 nd(0.0f);
          float w = 0.0f;
          bool any = false;
          for (std::size_t i = 0; i < rules.rules.size(); ++i) {
            const Rule& rule = rules.rules[i];
            if (rule.flatness != flatness || (!flatness && rule.style != style)) continue;
            nd = any ? nd + defuzzAt(defuzz, defuzz.row(rule), degrees[i])
                     : defuzzAt(defuzz, defuzz.row(rule), degrees[i]);
            w = any ? std::max(w, degrees[i]) : degrees[i];
            any = true;
          }
          return glm::vec2(w, nd.y > 0 ? nd.x / nd.y : 0.0f);
        };
        for (int s = 0; s < styleCount; ++s) {
          const glm::vec2 out = consequent(false, s);
          weight[std::size_t(s)] = out.x;
          styleValue[std::size_t(s)] = out.y;
        }
        const glm::vec2 flatness = consequent(true, -1);

        // Layers bottom to top, each over the ones below with opacity weight·α.
        const glm::vec2 uv = 0.5f + 0.5f * glm::vec2(eyeFromWorld * -direction);
        glm::vec4 layers(0.0f);
        float samplePriority = -1e30f, strongest = 0.0f, runnerUp = 0.0f;
        float runnerUpPriority = samplePriority;
        for (int s : order) {
          const float w = weight[std::size_t(s)];
          if (w <= 0.0f) continue;
          const float z =
              (float(atlas.firstLayer[std::size_t(s)]) +
               styleValue[std::size_t(s)] * float(atlas.sphereCount[std::size_t(s)] - 1) + 0.5f) /
              float(atlas.depth);
          const glm::vec4 c = semanticSampleAtlas(atlas, glm::vec3(uv, z));
          const float a = w * c.a;
          layers = glm::vec4(glm::vec3(c) * a, a) + layers * (1.0f - a);
          const float priority = float(rules.styles[std::size_t(s)].priority);
          if (a > 0.0f && a >= strongest) {
            runnerUp = strongest;
            runnerUpPriority = samplePriority;
            strongest = a;
            samplePriority = priority;
          } else if (a > runnerUp) {
            runnerUp = a;
            runnerUpPriority = priority;
          }
        }
        if (onPlane) {
          layers = glm::vec4(glm::vec3(data), 1.0f);
          samplePriority = topPriority;
          runnerUp = 0.0f;
        }
        if (layers.a <= 0.0f) continue;
        const float alpha = 1.0f - std::pow(1.0f - std::clamp(layers.a, 0.0f, 1.0f), exponent);
        const glm::vec3 color = glm::vec3(layers) / layers.a;
        const glm::vec4 src(glm::clamp(color, 0.0f, 1.0f) * alpha, alpha);
        if (flat) {
          if (runnerUp > 0.0f && strongest - runnerUp < kRegionEpsilon &&
              runnerUpPriority != samplePriority) {
            ambiguous = true;
          }
          if (samplePriority > top) {
            const float pf = interaction.flatness ? float(*interaction.flatness) : flatness.y;
            dst *= 1.0f - std::clamp(pf, 0.0f, 1.0f);
            top = samplePriority;
          }
        }
        dst += (1.0f - dst.a) * src;
      }
      result.frame.color(y, x) = cv::Vec4f(dst.r, dst.g, dst.b, dst.a);
      result.ambiguous(y, x) = ambiguous ? 1 : 0;
    }
  }
  return result;
}

}  // namespace vsil::reference
