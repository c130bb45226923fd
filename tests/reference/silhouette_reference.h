#pragma once
// CPU references of the `silhouette` (Nagy–Klein OPS) and `rightangle` techniques. They plan
// the same slices and sample the same positions as the GL path (slice_sampler.h), so results
// can be compared pixel by pixel.
#include "core/frame.h"
#include "core/volume.h"
#include "slicing/renderer.h"

namespace vsil::reference {

// Nagy–Klein Table 2: the intermediate state t combined with this slice's contour value c.
// Written independently of the shader's table, as the paper states it column by column.
PixelState decide(PixelState t, PixelState c);

struct ReferenceFrame {
  FrameBuffers frame;
  View view;
  int sliceCount = 0;
  // Pixels where the result hinges on a sample within `isoEpsilon` of the iso value (at this
  // pixel or, for the contour test, one of its 8 neighbours): there float rounding in the GL
  // rasteriser may legitimately decide the other way.
  cv::Mat1b ambiguous;
};

ReferenceFrame renderSilhouette(const Volume& volume, const RenderSettings& settings,
                                float isoEpsilon);
ReferenceFrame renderRightAngle(const Volume& volume, const RenderSettings& settings,
                                float isoEpsilon);

}  // namespace vsil::reference
