#include "reference_frame.h"

#include <cmath>
#include <limits>

#include "slice_sampler.h"

#include "slicing/technique_table.h"

namespace vsil::reference {

ReferenceSetup setUpReference(const Volume& volume, const RenderSettings& settings) {
  ReferenceSetup setup;
  setup.view = makeView(settings.camera, volume.dims, volume.spacing, settings.size);
  setup.plan = planSlices(setup.view, volume.dims, volume.spacing, settings.samplesPerVoxel);
  setup.options = OptionReader(findTechnique(settings.technique).options, settings.options,
                               derivedDefaults(volume));
  return setup;
}

ReferenceFrame emptyReferenceFrame(const ReferenceSetup& setup, glm::ivec2 size, bool color) {
  constexpr float kNan = std::numeric_limits<float>::quiet_NaN();
  ReferenceFrame result;
  result.view = setup.view;
  result.sliceCount = int(setup.plan.slices.size());
  result.ambiguous = cv::Mat1b(size.y, size.x, std::uint8_t(0));
  result.frame.depth = cv::Mat1f(size.y, size.x, kNan);
  if (color) {
    result.frame.color = cv::Mat4f(size.y, size.x, cv::Vec4f(0, 0, 0, 0));
  } else {
    result.frame.state = cv::Mat1b(size.y, size.x, std::uint8_t(PixelState::Empty));
    result.frame.shade = cv::Mat1f(size.y, size.x, kNan);
  }
  return result;
}

FirstHitFinder::FirstHitFinder(const ReferenceSetup& setup) : setup_(setup) {
  for (const Slice& slice : setup.plan.slices) {
    coords_.push_back(sliceVoxelCoords(setup.view, slice.eyeDistance));
  }
}

FirstHit FirstHitFinder::at(const SliceSampler& sampler, int x, int y, float iso,
                            float isoEpsilon) const {
  FirstHit hit;
  for (std::size_t k = 0; k < setup_.plan.slices.size(); ++k) {
    const Slice& slice = setup_.plan.slices[k];
    if (slice.polygonVoxel.empty()) continue;
    const glm::vec3 voxel = sampler.sliceVoxel(x, y, coords_[k]);
    if (!sampler.insideVolume(voxel)) continue;
    const float value = sampler.sample(voxel);
    if (std::abs(value - iso) <= isoEpsilon) hit.ambiguous = true;
    if (value < iso) continue;
    hit.slice = &slice;
    break;
  }
  return hit;
}

}  // namespace vsil::reference
