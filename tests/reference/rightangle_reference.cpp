#include "rightangle_reference.h"

#include <cmath>
#include <vector>

#include "slice_sampler.h"
#include "slicing/slicer.h"

namespace vsil::reference {

ReferenceFrame renderRightAngle(const Volume& volume, const RenderSettings& settings,
                                float isoEpsilon) {
  const ReferenceSetup setup = setUpReference(volume, settings);
  const float iso = float(setup.options.number("iso"));
  const float exponent = float(setup.options.number("ra-exponent"));
  const float threshold = float(setup.options.number("ra-threshold"));
  const SliceSampler sampler(volume, setup.view);
  const int w = settings.size.x, h = settings.size.y;
  ReferenceFrame result = emptyReferenceFrame(setup, settings.size);
  std::vector<SliceTexCoords> coords;
  for (const Slice& slice : setup.plan.slices) {
    coords.push_back(sliceTexCoords(setup.view, volume.dims, slice.eyeDistance));
  }
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      for (std::size_t k = 0; k < setup.plan.slices.size(); ++k) {
        const Slice& slice = setup.plan.slices[k];
        if (slice.polygonVoxel.empty()) continue;
        const glm::vec3 tex = sampler.sliceTexCoord(x, y, coords[k]);
        if (!sampler.insideTexture(tex)) continue;
        const float value = sampler.sampleTexture(tex);
        if (std::abs(value - iso) <= isoEpsilon) result.ambiguous(y, x) = 1;
        if (value < iso) continue;
        // The first hit is shaded where finish.frag shades it: at the eye point.
        const glm::vec3 eye = sampler.eyePoint(x, y, float(slice.eyeDistance));
        const glm::vec3 voxel = sampler.voxelFromEyePoint(eye);
        const float facing = sampler.facingRatio(voxel, eye);
        const bool line = std::pow(1.0f - facing, exponent) >
                          threshold;
        // A line decision within a hair of the threshold may also round either way.
        const float margin = std::abs(std::pow(1.0f - facing, exponent) -
                                      threshold);
        if (margin < 1e-4f) result.ambiguous(y, x) = 1;
        result.frame.state(y, x) = std::uint8_t(line ? PixelState::Silhouette : PixelState::Filled);
        result.frame.depth(y, x) = float(slice.depth);
        if (!line) result.frame.shade(y, x) = facing;
        break;
      }
    }
  }
  return result;
}

}  // namespace vsil::reference
