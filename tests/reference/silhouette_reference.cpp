#include "silhouette_reference.h"

#include <cmath>
#include <limits>
#include <vector>

#include "slice_sampler.h"
#include "slicing/slicer.h"

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

namespace {

constexpr float kNan = std::numeric_limits<float>::quiet_NaN();

struct Setup {
  View view;
  SlicePlan plan;
};

Setup setUp(const Volume& volume, const RenderSettings& settings) {
  Setup setup;
  setup.view = makeView(settings.camera, volume.dims, volume.spacing, settings.size);
  setup.plan = planSlices(setup.view, volume.dims, volume.spacing, settings.samplesPerVoxel);
  return setup;
}

// A frame of the setup's size with every pixel Empty (depth and shade NaN), nothing ambiguous.
ReferenceFrame emptyFrame(const Setup& setup, glm::ivec2 size) {
  ReferenceFrame result;
  result.view = setup.view;
  result.sliceCount = int(setup.plan.slices.size());
  result.ambiguous = cv::Mat1b(size.y, size.x, std::uint8_t(0));
  result.frame.state = cv::Mat1b(size.y, size.x, std::uint8_t(PixelState::Empty));
  result.frame.depth = cv::Mat1f(size.y, size.x, kNan);
  result.frame.shade = cv::Mat1f(size.y, size.x, kNan);
  return result;
}

}  // namespace

ReferenceFrame renderSilhouette(const Volume& volume, const RenderSettings& settings,
                                float isoEpsilon) {
  const Setup setup = setUp(volume, settings);
  const SliceSampler sampler(volume, setup.view);
  const int w = settings.size.x, h = settings.size.y;
  ReferenceFrame result = emptyFrame(setup, settings.size);
  cv::Mat1b state(h, w, std::uint8_t(PixelState::Empty));
  cv::Mat1f depth(h, w, 0.0f), shade(h, w, 0.0f);
  cv::Mat1b footprint(h, w), nearIso(h, w);

  auto step = [&](const Slice* slice, float previousDepth) {
    footprint = 0;
    nearIso = 0;
    if (slice) {
      const SliceTexCoords coords = sliceTexCoords(setup.view, volume.dims, slice->eyeDistance);
      for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
          const glm::vec3 tex = sampler.sliceTexCoord(x, y, coords);
          if (!sampler.insideTexture(tex)) continue;
          const float value = sampler.sampleTexture(tex);
          footprint(y, x) = value >= settings.iso;
          nearIso(y, x) = std::abs(value - settings.iso) <= isoEpsilon;
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
              const bool outside = nx < 0 || ny < 0 || nx >= w || ny >= h;
              if (!outside) hinges = hinges || nearIso(ny, nx);
              if (outside || !footprint(ny, nx)) c = PixelState::Contour;
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
          shade(y, x) = sampler.facingRatio(sampler.voxelFromEyePoint(eye), eye);
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
    }
  }
  return result;
}

ReferenceFrame renderRightAngle(const Volume& volume, const RenderSettings& settings,
                                float isoEpsilon) {
  const Setup setup = setUp(volume, settings);
  const SliceSampler sampler(volume, setup.view);
  const int w = settings.size.x, h = settings.size.y;
  ReferenceFrame result = emptyFrame(setup, settings.size);
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
        if (std::abs(value - settings.iso) <= isoEpsilon) result.ambiguous(y, x) = 1;
        if (value < settings.iso) continue;
        // The first hit is shaded where finish.frag shades it: at the eye point.
        const glm::vec3 eye = sampler.eyePoint(x, y, float(slice.eyeDistance));
        const glm::vec3 voxel = sampler.voxelFromEyePoint(eye);
        const float facing = sampler.facingRatio(voxel, eye);
        const bool line = std::pow(1.0f - facing, float(settings.rightAngleExponent)) >
                          float(settings.rightAngleThreshold);
        // A line decision within a hair of the threshold may also round either way.
        const float margin = std::abs(std::pow(1.0f - facing, float(settings.rightAngleExponent)) -
                                      float(settings.rightAngleThreshold));
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
