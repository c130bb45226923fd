#include "firsthit_reference.h"

#include "slice_sampler.h"

namespace vsil::reference {

ReferenceFrame renderFirstHit(const Volume& volume, const RenderSettings& settings,
                              float isoEpsilon) {
  const ReferenceSetup setup = setUpReference(volume, settings);
  const float iso = float(setup.options.number("iso"));
  const SliceSampler sampler(volume, setup.view);
  const FirstHitFinder firstHits(setup);
  ReferenceFrame result = emptyReferenceFrame(setup, settings.size, /*color=*/true);
  for (int y = 0; y < settings.size.y; ++y) {
    for (int x = 0; x < settings.size.x; ++x) {
      const FirstHit hit = firstHits.at(sampler, x, y, iso, isoEpsilon);
      if (hit.ambiguous) result.ambiguous(y, x) = 1;
      if (!hit.slice) continue;
      const float depth = float(hit.slice->depth);
      const float grey = 1.0f - depth;
      result.frame.depth(y, x) = depth;
      result.frame.color(y, x) = cv::Vec4f(grey, grey, grey, 1.0f);
    }
  }
  return result;
}

}  // namespace vsil::reference
