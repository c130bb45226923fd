#include "rightangle_reference.h"

#include <cmath>

#include "slice_sampler.h"
#include "tone_fill_reference.h"

namespace vsil::reference {

ReferenceFrame renderRightAngle(const Volume& volume, const RenderSettings& settings,
                                float isoEpsilon) {
  const ReferenceSetup setup = setUpReference(volume, settings);
  const float iso = float(setup.options.number("iso"));
  const float exponent = float(setup.options.number("ra-exponent"));
  const float threshold = float(setup.options.number("ra-threshold"));
  const SliceSampler sampler(volume, setup.view);
  const FirstHitFinder firstHits(setup);
  const ToneFillReference toneFill(settings, setup);
  ReferenceFrame result = emptyReferenceFrame(setup, settings.size);
  result.frame.tone = toneFill.emptyImage(settings.size);
  for (int y = 0; y < settings.size.y; ++y) {
    for (int x = 0; x < settings.size.x; ++x) {
      const FirstHit hit = firstHits.at(sampler, x, y, iso, isoEpsilon);
      if (hit.ambiguous) result.ambiguous(y, x) = 1;
      if (!hit.slice) continue;
      // The first hit is shaded where finish_hits.frag shades it: at the eye point.
      const glm::vec3 eye = sampler.eyePoint(x, y, float(hit.slice->eyeDistance));
      const glm::vec3 voxel = quantizedVoxel(sampler.voxelFromEyePoint(eye));
      const float facing = sampler.facingRatio(voxel, eye);
      const float lineness = std::pow(1.0f - facing, exponent);
      const bool line = lineness > threshold;
      // A line decision within a hair of the threshold may also round either way.
      if (std::abs(lineness - threshold) < 1e-4f) result.ambiguous(y, x) = 1;
      result.frame.state(y, x) = std::uint8_t(line ? PixelState::Silhouette : PixelState::Filled);
      result.frame.depth(y, x) = float(hit.slice->depth);
      if (!line) result.frame.shade(y, x) = facing;
      if (!line && toneFill.active()) {
        const glm::vec3 c =
            toneFill.at(sampler, x, y, float(hit.slice->eyeDistance), float(hit.slice->depth));
        result.frame.tone(y, x) = cv::Vec3f(c.r, c.g, c.b);
      }
    }
  }
  return result;
}

}  // namespace vsil::reference
