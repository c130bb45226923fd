#include "mip_reference.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "slice_sampler.h"
#include "slicing/techniques/mip/colour_sphere.h"
#include "slicing/techniques/mip/mip_options.h"
#include "slicing/transfer_function_texture.h"

namespace vsil::reference {

namespace {

// The samples pixel (x, y) sees, front to back, with their slices. `low` and `high` bound what
// the shader may sample there instead: its position may round to a neighbouring 1/1024 voxel
// (SliceSampler::rayVoxelCandidates).
struct RaySample {
  const Slice* slice;
  float value;
  float low, high;
};

class RaySampler {
 public:
  RaySampler(const Volume& volume, const ReferenceSetup& setup)
      : setup_(setup),
        sampler_(volume, setup.view),
        rays_(pixelRays(setup.view, setup.plan)),
        dims_(volume.dims) {}
  // `onBoxFace` turns true when a sample position lies within kFaceEpsilon of the box's faces:
  // whether the rasteriser covers such a pixel with the slice polygon is a matter of rounding,
  // and every sample counts for a maximum (for the iso-surface techniques it would not, as the
  // values there lie far below the iso value).
  std::vector<RaySample> along(int x, int y, bool& onBoxFace) const {
    // Voxels: two steps of the sample positions' rounding (BrickLayout::kSampleQuantum), which
    // the shader's float rounding before it may tip either way.
    constexpr float kFaceEpsilon = 2.0f / 1024.0f;
    std::vector<RaySample> samples;
    for (std::size_t k = 0; k < setup_.plan.slices.size(); ++k) {
      const Slice& slice = setup_.plan.slices[k];
      if (slice.polygonVoxel.empty()) continue;
      const VoxelCandidates candidates = sampler_.rayVoxelCandidates(x, y, rays_, int(k));
      const glm::vec3 voxel = candidates.positions[0];
      // Distance to the nearer face per axis.
      const glm::vec3 inner = glm::min(voxel + 0.5f, dims_ - 0.5f - voxel);
      const float nearest = std::min({inner.x, inner.y, inner.z});
      if (std::abs(nearest) < kFaceEpsilon) onBoxFace = true;
      if (!sampler_.insideVolume(voxel)) continue;
      RaySample sample{&slice, sampler_.sample(voxel), 0, 0};
      sample.low = sample.high = sample.value;
      for (int i = 1; i < candidates.count; ++i) {
        const glm::vec3 other = candidates.positions[std::size_t(i)];
        if (!sampler_.insideVolume(other)) continue;  // near a face: onBoxFace
        const float value = sampler_.sample(other);
        sample.low = std::min(sample.low, value);
        sample.high = std::max(sample.high, value);
      }
      samples.push_back(sample);
    }
    return samples;
  }
  const SliceSampler& sampler() const { return sampler_; }

 private:
  const ReferenceSetup& setup_;
  SliceSampler sampler_;
  PixelRays rays_;  // the MIP family samples along rays (common.glsl RAY_SAMPLING)
  glm::vec3 dims_;
};

float maximumOf(const std::vector<RaySample>& samples,
                float RaySample::*bound = &RaySample::value) {
  float maximum = -std::numeric_limits<float>::infinity();
  for (const auto& s : samples) maximum = std::max(maximum, s.*bound);
  return maximum;
}

// mip_finish.frag's classification of a pixel's value: the window's grey ramp, opacity 1 above
// its low end; or --tf's table, read as GL reads the 1D texture.
class Classification {
 public:
  Classification(const OptionReader& options, ValueRange range)
      : window_(intensityWindow(options)) {
    if (const auto tf = mipTransferFunction(options)) {
      table_ = tf->table(range, TransferFunctionTexture::kEntries);
      tableCoord_ = TransferFunctionTexture::coordinateFromValue(range);
    }
  }
  // Straight colour and opacity; opacity 0 shows nothing.
  glm::vec4 operator()(float value) const {
    if (!table_.empty()) return sampleTable(table_, value * tableCoord_.x + tableCoord_.y);
    if (!(value > window_.low)) return glm::vec4(0.0f);
    const float grey = std::clamp((value - window_.low) / (window_.high - window_.low), 0.0f, 1.0f);
    return {grey, grey, grey, 1.0f};
  }
  // Where rounding may decide whether a value shows (the window's low end).
  bool nearEdge(float value, float isoEpsilon) const {
    return table_.empty() && std::abs(value - window_.low) <= isoEpsilon;
  }

 private:
  IntensityWindow window_;
  std::vector<glm::vec4> table_;
  glm::vec2 tableCoord_{0.0f};
};

// An equirectangular sphere map (--sphere-map FILE.png) toward `d`, given in the sphere's frame
// (x right, y up, z front): longitude atan2(x, z) across the width from the left edge (−180°),
// latitude atan2(y, |(x, z)|) down from the top row (+90°), read as GL_LINEAR reads the
// texture: between texel centres, wrapping around in longitude, clamped in latitude.
glm::vec3 equirectangularColour(const SphereMapImage& map, glm::vec3 d) {
  constexpr float kPi = 3.14159265358979f;
  float u = 0.5f, v = 0.5f;  // the centre of the volume has no direction: the image's centre
  if (glm::dot(d, d) > 0) {
    const float longitude = d.x != 0 || d.z != 0 ? std::atan2(d.x, d.z) : 0.0f;
    u = 0.5f + longitude / (2 * kPi);
    v = 0.5f - std::atan2(d.y, std::sqrt(d.x * d.x + d.z * d.z)) / kPi;
  }
  const float column = u * float(map.width) - 0.5f;
  const float left = std::floor(column);
  const auto wrapped = [&](int i) { return ((i % map.width) + map.width) % map.width; };
  const int x0 = wrapped(int(left)), x1 = wrapped(int(left) + 1);
  const LinearTaps rows = linearTaps(v, map.height);  // clamped to the edge rows
  const float fx = column - left;
  const auto row = [&](int y) { return map.at(x0, y) * (1 - fx) + map.at(x1, y) * fx; };
  return row(rows.i0) * (1 - rows.f) + row(rows.i1) * rows.f;
}

cv::Vec4f premultiplied(glm::vec3 colour, float opacity) {
  return {colour.r * opacity, colour.g * opacity, colour.b * opacity, opacity};
}

// Normalized depth where the pixel's ray enters the box −0.5 .. dims − 0.5 (0 in front of it),
// and the entry point in voxels: the ray from d = 0 to d = 1 is linear in d.
float boxEntry(const SliceSampler& sampler, const View& view, glm::vec3 dims, int x, int y,
               glm::vec3& entryVoxel) {
  const glm::vec3 a = sampler.voxelFromEyePoint(sampler.eyePoint(x, y, float(view.nearEye)));
  const glm::vec3 b = sampler.voxelFromEyePoint(sampler.eyePoint(x, y, float(view.farEye)));
  float entry = 0.0f;
  for (int axis = 0; axis < 3; ++axis) {
    const float direction = b[axis] - a[axis];
    if (direction == 0.0f) continue;
    const float t0 = (-0.5f - a[axis]) / direction;
    const float t1 = (dims[axis] - 0.5f - a[axis]) / direction;
    entry = std::max(entry, std::min(t0, t1));
  }
  entryVoxel = a + entry * (b - a);
  return entry;
}

ReferenceFrame render(const Volume& volume, const RenderSettings& settings, float isoEpsilon,
                      bool depthEnhanced) {
  const ReferenceSetup setup = setUpReference(volume, settings);
  const OptionReader& options = setup.options;
  const Classification classify(options, valueRange(volume));
  const RaySampler rays(volume, setup);
  ReferenceFrame result = emptyReferenceFrame(setup, settings.size, /*color=*/true);
  const View& view = setup.view;
  const glm::mat4 clipFromVoxel(view.clipFromVoxel());
  const glm::vec3 centreEye(view.eyeFromWorld * glm::dvec4(0, 0, 0, 1));
  // The map's colours or texels as the technique reads them (the file read once, by the
  // engine's reader); what a direction picks is computed here.
  const ColourSphere sphereMap =
      depthEnhanced ? colourSphere(options.text("sphere-map")) : ColourSphere{};
  const glm::mat3 sphereFromEye =
      depthEnhanced ? glm::transpose(sphereFrameEye(options, view)) : glm::mat3(1.0f);
  for (int y = 0; y < settings.size.y; ++y) {
    for (int x = 0; x < settings.size.x; ++x) {
      bool onBoxFace = false;
      const std::vector<RaySample> samples = rays.along(x, y, onBoxFace);
      if (onBoxFace) result.ambiguous(y, x) = 1;
      if (samples.empty()) continue;
      const float maximum = maximumOf(samples);
      // The shader's maximum lies between these (its positions may round otherwise).
      const float lowest = maximumOf(samples, &RaySample::low);
      const float highest = maximumOf(samples, &RaySample::high);
      if (highest - lowest > isoEpsilon) result.ambiguous(y, x) = 1;
      if (classify.nearEdge(maximum, isoEpsilon)) result.ambiguous(y, x) = 1;
      const glm::vec4 classified = classify(maximum);
      if (!(classified.a > 0)) continue;
      glm::vec3 colour(classified);
      if (depthEnhanced) {
        const float eps = float(options.number("material-eps"));
        const float threshold = maximum - eps;
        const RaySample* hit = nullptr;
        for (const auto& s : samples) {
          // Whether the shader may count this sample as of the material and may not: its value
          // and the threshold each within their bounds, widened by float rounding.
          const bool may = s.high + isoEpsilon >= lowest - eps;
          const bool must = s.low - isoEpsilon >= highest - eps;
          if (may && !must) result.ambiguous(y, x) = 1;
          if (s.value >= threshold) {
            hit = &s;
            break;
          }
        }
        const float hitDepth = float(hit->slice->depth);
        result.frame.depth(y, x) = hitDepth;
        float depth = hitDepth;
        const DepthMode mode = depthMode(options);
        if (mode != DepthMode::Exact) {
          glm::vec3 entryVoxel;
          const float entry =
              boxEntry(rays.sampler(), view, glm::vec3(volume.dims), x, y, entryVoxel);
          depth = hitDepth - entry;  // the ray's length inside the box before the hit
          if (mode == DepthMode::EntryPlusSteps) {
            const glm::vec4 clip = clipFromVoxel * glm::vec4(entryVoxel, 1.0f);
            depth += clip.z / clip.w * 0.5f + 0.5f;  // the entry's OpenGL window depth
          }
        }
        const float weight = float(options.number("depth-weight"));
        const glm::vec3 c =
            glm::clamp(colour * (1 - weight) + 2 * weight * (1 - depth), 0.0f, 1.0f);
        // Colour sphere: the direction from the volume's centre to the hit picks the blend
        // between the map's front and back colours, or the image's texels.
        const glm::vec3 hitEye = rays.sampler().eyePoint(x, y, float(hit->slice->eyeDistance));
        const glm::vec3 fromCentre = hitEye - centreEye;
        glm::vec3 sphere;
        if (sphereMap.image) {
          sphere = equirectangularColour(*sphereMap.image, sphereFromEye * fromCentre);
        } else {
          const float facing =
              glm::dot(fromCentre, fromCentre) > 0
                  ? glm::dot(glm::normalize(fromCentre), sphereFrontEye(options, view))
                  : 0.0f;
          sphere = glm::mix(sphereMap.back, sphereMap.front, 0.5f + 0.5f * facing);
        }
        const float sphereWeight = float(options.number("sphere-weight"));
        colour = c * (1 - sphereWeight) + sphere * sphereWeight;
      }
      result.frame.color(y, x) = premultiplied(colour, classified.a);
    }
  }
  return result;
}

}  // namespace

ReferenceFrame renderMip(const Volume& volume, const RenderSettings& settings, float isoEpsilon) {
  return render(volume, settings, isoEpsilon, /*depthEnhanced=*/false);
}

ReferenceFrame renderDemip(const Volume& volume, const RenderSettings& settings, float isoEpsilon) {
  return render(volume, settings, isoEpsilon, /*depthEnhanced=*/true);
}

ReferenceFrame renderLmip(const Volume& volume, const RenderSettings& settings, float isoEpsilon) {
  const ReferenceSetup setup = setUpReference(volume, settings);
  const Classification classify(setup.options, valueRange(volume));
  const float threshold = lmipThreshold(setup.options);
  const RaySampler rays(volume, setup);
  ReferenceFrame result = emptyReferenceFrame(setup, settings.size, /*color=*/true);
  for (int y = 0; y < settings.size.y; ++y) {
    for (int x = 0; x < settings.size.x; ++x) {
      bool onBoxFace = false;
      const std::vector<RaySample> samples = rays.along(x, y, onBoxFace);
      if (onBoxFace) result.ambiguous(y, x) = 1;
      if (samples.empty()) continue;
      const RaySample* top = nullptr;  // the highest sample of the run above the threshold
      // Whether values within these bounds (the shader's may round otherwise: RaySample) may
      // compare either way with one another, up to float rounding.
      const auto close = [isoEpsilon](float low, float high, float otherLow, float otherHigh) {
        return high + isoEpsilon >= otherLow && low - isoEpsilon <= otherHigh;
      };
      for (const auto& s : samples) {
        if (close(s.low, s.high, threshold, threshold)) result.ambiguous(y, x) = 1;
        if (top && close(s.low, s.high, top->low, top->high)) result.ambiguous(y, x) = 1;
        if (top && s.value < top->value) break;  // the run falls: top is the local maximum
        if (s.value >= threshold && (!top || s.value > top->value)) top = &s;
      }
      // The value shown may be open too: the local maximum's own, or without a run the plain
      // maximum, as mip's.
      const float shownLow = top ? top->low : maximumOf(samples, &RaySample::low);
      const float shownHigh = top ? top->high : maximumOf(samples, &RaySample::high);
      if (shownHigh - shownLow > isoEpsilon) result.ambiguous(y, x) = 1;
      const float shown = top ? top->value : maximumOf(samples);
      if (classify.nearEdge(shown, isoEpsilon)) result.ambiguous(y, x) = 1;
      const glm::vec4 classified = classify(shown);
      if (!(classified.a > 0)) continue;
      result.frame.color(y, x) = premultiplied(glm::vec3(classified), classified.a);
      if (top) result.frame.depth(y, x) = float(top->slice->depth);
    }
  }
  return result;
}

}  // namespace vsil::reference
