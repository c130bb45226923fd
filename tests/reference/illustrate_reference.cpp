#include "illustrate_reference.h"

#include <algorithm>
#include <cmath>

#include "core/illustration.h"
#include "illustration_formulas.h"
#include "slice_sampler.h"
#include "slicing/gradient_texture.h"
#include "slicing/illustration_options.h"
#include "slicing/technique_table.h"
#include "slicing/techniques/illustrate/halo_mask.h"
#include "slicing/techniques/illustrate/illustrate_technique.h"
#include "slicing/transfer_function_texture.h"

namespace vsil::reference {
namespace {

// The voxel nearest to a voxel position (composite.frag nearestTexel), clamped to the volume.
glm::ivec3 nearestTexel(glm::vec3 voxel, glm::ivec3 dims) {
  return glm::clamp(glm::ivec3(glm::floor(voxel + 0.5f)), glm::ivec3(0), dims - 1);
}

}  // namespace

ReferenceFrame renderIllustrate(const Volume& volume, const RenderSettings& settings, float) {
  const ReferenceSetup setup = setUpReference(volume, settings);
  const TechniqueInfo& technique = findTechnique("illustrate");
  const Illustration ill = illustrationFromOptions(technique.options, setup.options);
  const View& view = setup.view;
  const ValueRange range = valueRange(volume);
  const SliceSampler sampler(volume, view);
  const std::vector<float> texels = textureTexels(volume);
  // The values come from the volume's own texels (sampler.sample), whether or not the GL path
  // reads them from the gradient texture.
  const GradientTexels gradients =
      computeGradientTexels(texels.data(), volume.dims, volume.spacing, /*withValues=*/false);
  const Rgba background = settings.background.value_or(ill.background.value_or(kDefaultBackground));

  const glm::mat3 worldFromEye(glm::transpose(glm::dmat3(view.eyeFromWorld)));
  IllustrationFormulas formulas{ill, {}, ill.sketchColor.rgb01(), background.rgb01()};
  for (const Light& light : ill.lights) {
    formulas.lights.push_back(worldFromEye * glm::vec3(light.directionEye()));
  }
  const auto has = [&](Effect e) { return ill.effects.has(e); };
  const bool exactHalo = setup.options.text("halo-mode") == "exact";

  // Classification: the transfer function's table sampled linearly, or o_v = k_os·v^k_oe.
  std::vector<glm::vec4> table;
  glm::vec2 tableCoord(0.0f);
  if (ill.transferFunction) {
    table = ill.transferFunction->table(range, TransferFunctionTexture::kEntries);
    tableCoord = TransferFunctionTexture::coordinateFromValue(range);
  }
  const ValueRange domain = powerOpacityDomain(ill, range);
  const double span = double(domain.max) - double(domain.min);
  const float valueScale = span > 0 ? float(1.0 / span) : 0.0f;  // as the uniform
  const auto classify = [&](float value) -> glm::vec4 {
    if (ill.transferFunction) {
      return sampleTable(table, value * tableCoord.x + tableCoord.y);
    }
    const float v = std::clamp((value - domain.min) * valueScale, 0.0f, 1.0f);
    return glm::vec4(ill.color.rgb01(), float(ill["k_os"]) * std::pow(v, float(ill["k_oe"])));
  };

  // Halos: exact, taps in the slice plane and the mask of where they may appear; field, the
  // halo field's RGBA bytes per voxel (halo_mask.h haloFieldVoxels, what the GL path uploads).
  struct Tap {
    glm::vec3 offset, direction;
    float weight;
  };
  std::vector<Tap> taps;
  std::vector<std::uint8_t> mask, field;
  if (has(Effect::Halo) && !exactHalo) {
    mask =
        haloMaskVoxels(texels.data(), volume.dims, visibleValues(ill, table, range), ill["k_hr"]);
    field = haloFieldVoxels(gradients, mask, texels.data(), transparentValues(ill, table, range),
                            volume.spacing, ill["k_hr"], ill["k_hpe"]);
  }
  if (has(Effect::Halo) && exactHalo) {
    const glm::dmat3 voxelFromEye = glm::inverse(glm::dmat3(view.eyeFromVoxel));
    for (const HaloTap& tap : haloTaps(ill["k_hr"])) {
      const glm::dvec3 eye(tap.offsetEye, 0.0);
      const glm::dvec3 voxel = glm::normalize(voxelFromEye * eye) * tap.distanceVoxels;
      taps.push_back({glm::vec3(voxel), worldFromEye * glm::vec3(-eye), float(tap.weight)});
    }
    mask =
        haloMaskVoxels(texels.data(), volume.dims, visibleValues(ill, table, range), ill["k_hr"]);
  }
  const auto voxelIndex = [&](glm::ivec3 t) {
    return (std::size_t(t.z) * std::size_t(volume.dims.y) + std::size_t(t.y)) *
               std::size_t(volume.dims.x) +
           std::size_t(t.x);
  };
  const auto maskAt = [&](glm::ivec3 t) { return float(mask[voxelIndex(t)]); };

  const float exponent = float(setup.plan.stepVoxels);
  // Samples on each pixel's ray, aligned to its entry into the box (BOX_ALIGNED_SAMPLING).
  const PixelRays rays = pixelRays(view, setup.plan);
  ReferenceFrame result = emptyReferenceFrame(setup, settings.size, /*color=*/true);
  for (int y = 0; y < settings.size.y; ++y) {
    for (int x = 0; x < settings.size.x; ++x) {
      glm::vec4 dst(0.0f);
      const SliceSampler::BoxAlignedRay ray = sampler.boxAlignedRay(x, y, rays);
      if (ray.phaseAmbiguous) result.ambiguous(y, x) = 1;
      for (std::size_t k = 0; k < setup.plan.slices.size(); ++k) {
        const Slice& slice = setup.plan.slices[k];
        if (slice.polygonVoxel.empty()) continue;
        const glm::vec3 voxel = SliceSampler::boxAlignedVoxel(ray, int(k));
        if (!sampler.insideVolume(voxel)) continue;
        const std::uint8_t* fieldBytes =
            field.empty() ? nullptr : &field[4 * voxelIndex(nearestTexel(voxel, volume.dims))];
        if (fieldBytes && fieldBytes[3] == 0) continue;  // no halo and transparent
        const glm::vec4 material = classify(sampler.sample(voxel));
        const float nearFeature = fieldBytes          ? (fieldBytes[3] > 1 ? 1.0f : 0.0f)
                                  : has(Effect::Halo) ? maskAt(nearestTexel(voxel, volume.dims))
                                                      : 0;
        if (material.a <= 0 && nearFeature <= 0) continue;  // adds nothing

        const SplitGradient g = splitGradient(sampleGradientTexels(gradients, voxel));
        const glm::vec3 n = -g.direction;
        const float magnitude = g.magnitude;
        const glm::vec3 toViewer =
            view.orthographic ? glm::vec3(0, 0, 1)
                              : -glm::normalize(sampler.eyePoint(x, y, float(slice.eyeDistance)));
        const glm::vec3 v = worldFromEye * toViewer;
        const float facing = g.hasDirection ? std::abs(glm::dot(n, v)) : 1.0f;  // none: facing

        float opacity = material.a;
        glm::vec3 base(material);
        if (has(Effect::Boundary)) opacity = formulas.boundary(opacity, magnitude);
        if (has(Effect::Silhouette)) opacity = formulas.silhouette(opacity, facing);
        if (has(Effect::Fading)) formulas.fading(base, opacity, facing);
        glm::vec3 color = formulas.lit(base, n);
        if (has(Effect::Tone)) color = formulas.tone(color, base, n);
        if (has(Effect::Sketch)) formulas.sketchLines(color, opacity, facing, magnitude);
        if (has(Effect::Distance)) color = formulas.distance(color, float(slice.depth));
        if (fieldBytes) {
          // h = F·(1 − |N·V|)^k_hse·(1 − |∇f|), F and N from the field's bytes.
          const glm::vec3 fieldNormal = haloFieldNormal(fieldBytes);
          const float across = std::max(1.0f - std::abs(glm::dot(fieldNormal, v)), 0.0f);
          const float h = haloFieldStrength(fieldBytes[3]) * std::pow(across, formulas.p("k_hse")) *
                          (1.0f - magnitude);
          formulas.halo(color, opacity, h);
        } else if (has(Effect::Halo)) {
          // h = Σ w_n·|∇f_n|·(n_n·d)^k_hpe·(1 − |n_n·V|)^k_hse, times (1 − |∇f|) here.
          float h = 0;
          for (const Tap& tap : taps) {
            const glm::ivec3 t = nearestTexel(voxel + tap.offset, volume.dims);
            const SplitGradient gn = splitGradient(gradients.at(t.x, t.y, t.z));
            const glm::vec3 nn = -gn.direction;
            const float towards = std::max(glm::dot(nn, tap.direction), 0.0f);
            const float across = std::max(1.0f - std::abs(glm::dot(nn, v)), 0.0f);
            h += tap.weight * gn.magnitude * std::pow(towards, formulas.p("k_hpe")) *
                 std::pow(across, formulas.p("k_hse"));
          }
          h *= (1.0f - magnitude) * nearFeature;
          formulas.halo(color, opacity, h);
        }
        // α = 1 − (1 − o)^(Δ/Δ₀), premultiplied, behind what is there.
        const float alpha = 1.0f - std::pow(1.0f - std::clamp(opacity, 0.0f, 1.0f), exponent);
        const glm::vec4 src(glm::clamp(color, 0.0f, 1.0f) * alpha, alpha);
        dst += (1.0f - dst.a) * src;
      }
      result.frame.color(y, x) = cv::Vec4f(dst.r, dst.g, dst.b, dst.a);
    }
  }
  return result;
}

}  // namespace vsil::reference
