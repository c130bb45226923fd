#include "silhouette_reference.h"

#include <cmath>
#include <vector>

#include "slice_sampler.h"
#include "slicing/slicer.h"
#include "tone_fill_reference.h"

namespace vsil::reference {

PixelState decide(PixelState t, PixelState c) {
  switch (t) {
    case PixelState::Empty:  // empty pixels are always overdrawn
      return c;
    case PixelState::Filled:  // filled pixels are never overdrawn
      return PixelState::Filled;
    case PixelState::Contour:
      if (c == PixelState::Empty) return PixelState::Silhouette;  // nothing behind: detection
      if (c == PixelState::Filled) return PixelState::Filled;     // the surface goes on
      return PixelState::Contour;                                 // propagation
    case PixelState::Silhouette:  // silhouettes propagate unconditionally
      return PixelState::Silhouette;
  }
  return t;
}

ReferenceFrame renderSilhouette(const Volume& volume, const RenderSettings& settings,
                                float isoEpsilon) {
  const ReferenceSetup setup = setUpReference(volume, settings);
  const float iso = float(setup.options.number("iso"));
  const SliceSampler sampler(volume, setup.view);
  const int w = settings.size.x, h = settings.size.y;
  const ToneFillReference toneFill(settings, setup);
  ReferenceFrame result = emptyReferenceFrame(setup, settings.size);
  result.frame.tone = toneFill.emptyImage(settings.size);
  cv::Mat1b state(h, w, std::uint8_t(PixelState::Empty));
  cv::Mat1f depth(h, w, 0.0f), shade(h, w, 0.0f);
  cv::Mat3f tone = result.frame.tone.clone();
  cv::Mat1b footprint(h, w), nearIso(h, w);

  auto step = [&](const Slice* slice, float previousDepth) {
    footprint = 0;
    nearIso = 0;
    if (slice) {
      const SliceVoxelCoords coords = sliceVoxelCoords(setup.view, slice->eyeDistance);
      for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
          const glm::vec3 voxel = sampler.sliceVoxel(x, y, coords);
          if (!sampler.insideVolume(voxel)) continue;
          const float value = sampler.sample(voxel);
          footprint(y, x) = value >= iso;
          nearIso(y, x) = std::abs(value - iso) <= isoEpsilon;
        }
      }
    }
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        PixelState c = PixelState::Empty;
        bool hinges = false;
        if (footprint(y, x)) {
          c = PixelState::Filled;
          for (int dy = -1; dy <= 1; ++dy) {
            for (int dx = -1; dx <= 1; ++dx) {
              const int nx = x + dx, ny = y + dy;
              // Beyond the image nothing is known: no neighbour there (silhouette.glsl).
              if (nx < 0 || ny < 0 || nx >= w || ny >= h) continue;
              hinges = hinges || nearIso(ny, nx);
              if (!footprint(ny, nx)) c = PixelState::Contour;
            }
          }
        }
        hinges = hinges || nearIso(y, x);
        const auto t = PixelState(state(y, x));
        const PixelState next = decide(t, c);
        if (hinges && t != PixelState::Filled && t != PixelState::Silhouette) {
          result.ambiguous(y, x) = 1;
        }
        if (t == PixelState::Empty && next != PixelState::Empty) {
          const glm::vec3 eye = sampler.eyePoint(x, y, float(slice->eyeDistance));
          depth(y, x) = float(slice->depth);
          shade(y, x) = sampler.facingRatio(quantizedVoxel(sampler.voxelFromEyePoint(eye)), eye);
          if (toneFill.active()) {
            const glm::vec3 c =
                toneFill.at(sampler, x, y, float(slice->eyeDistance), float(slice->depth));
            tone(y, x) = cv::Vec3f(c.r, c.g, c.b);
          }
        } else if (t == PixelState::Contour && next == PixelState::Silhouette) {
          depth(y, x) = 0.5f * (depth(y, x) + previousDepth);
        }
        state(y, x) = std::uint8_t(next);
      }
    }
  };

  float previousDepth = 0;
  for (const Slice& slice : setup.plan.slices) {
    step(slice.polygonVoxel.empty() ? nullptr : &slice, previousDepth);
    previousDepth = float(slice.depth);
  }
  step(nullptr, previousDepth);  // the extra empty slice

  result.frame.state = state;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const auto s = PixelState(state(y, x));
      if (s != PixelState::Empty) result.frame.depth(y, x) = depth(y, x);
      if (s == PixelState::Filled) result.frame.shade(y, x) = shade(y, x);
      if (s == PixelState::Filled && toneFill.active()) result.frame.tone(y, x) = tone(y, x);
    }
  }
  return result;
}

}  // namespace vsil::reference
