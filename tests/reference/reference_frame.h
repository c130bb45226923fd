#pragma once
// What every CPU reference shares: the frame it returns, the same view and slice plan as the
// GL path, and the technique's options resolved as the Renderer resolves them.
#include <vector>

#include <opencv2/core.hpp>

#include "core/frame.h"
#include "core/options.h"
#include "core/volume.h"
#include "slicing/renderer.h"
#include "slicing/slicer.h"

namespace vsil::reference {

struct ReferenceFrame {
  FrameBuffers frame;
  View view;
  int sliceCount = 0;
  // Pixels where the result hinges on a sample within `isoEpsilon` of a decision threshold (the
  // iso value at this pixel or, for the contour test, one of its 8 neighbours): there float
  // rounding in the GL rasteriser may legitimately decide the other way.
  cv::Mat1b ambiguous;
};

struct ReferenceSetup {
  View view;
  SlicePlan plan;
  OptionReader options;  // the technique's options, defaults resolved as the Renderer does
};

ReferenceSetup setUpReference(const Volume& volume, const RenderSettings& settings);

// A frame of the setup's size with every pixel Empty (depth and shade NaN), nothing ambiguous;
// with `color`, a transparent colour image and no state image instead.
ReferenceFrame emptyReferenceFrame(const ReferenceSetup& setup, glm::ivec2 size,
                                   bool color = false);

class SliceSampler;

// The first sample at or above `iso` along pixel (x, y)'s ray, front to back over the setup's
// slices (what shaders/first_hit.frag keeps): its slice, or null when the ray finds none.
// `ambiguous` turns true when a sample on the way lies within `isoEpsilon` of `iso`.
struct FirstHit {
  const Slice* slice = nullptr;
  bool ambiguous = false;
};
class FirstHitFinder {
 public:
  explicit FirstHitFinder(const ReferenceSetup& setup);
  FirstHit at(const SliceSampler& sampler, int x, int y, float iso, float isoEpsilon) const;

 private:
  const ReferenceSetup& setup_;
  std::vector<SliceVoxelCoords> coords_;  // per slice
};

}  // namespace vsil::reference
