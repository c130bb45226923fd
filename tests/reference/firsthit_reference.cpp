#include "firsthit_reference.h"

#include <cmath>
#include <vector>

#include "slice_sampler.h"

namespace vsil::reference {

ReferenceFrame renderFirstHit(const Volume& volume, const RenderSettings& settings,
                              float isoEpsilon) {
  const ReferenceSetup setup = setUpReference(volume, settings);
  const float iso = float(setup.options.number("iso"));
  const SliceSampler sampler(volume, setup.view);
  ReferenceFrame result = emptyReferenceFrame(setup, settings.size, /*color=*/true);
  std::vector<SliceTexCoords> coords;
  for (const Slice& slice : setup.plan.slices) {
    coords.push_back(sliceTexCoords(setup.view, volume.dims, slice.eyeDistance));
  }
  for (int y = 0; y < settings.size.y; ++y) {
    for (int x = 0; x < settings.size.x; ++x) {
      for (std::size_t k = 0; k < setup.plan.slices.size(); ++k) {
        const Slice& slice = setup.plan.slices[k];
        if (slice.polygonVoxel.empty()) continue;
        const glm::vec3 tex = sampler.sliceTexCoord(x, y, coords[k]);
        if (!sampler.insideTexture(tex)) continue;
        const float value = sampler.sampleTexture(tex);
        if (std::abs(value - iso) <= isoEpsilon) result.ambiguous(y, x) = 1;
        if (value < iso) continue;
        const float depth = float(slice.depth);
        const float grey = 1.0f - depth;
        result.frame.depth(y, x) = depth;
        result.frame.color(y, x) = cv::Vec4f(grey, grey, grey, 1.0f);
        break;
      }
    }
  }
  return result;
}

}  // namespace vsil::reference
