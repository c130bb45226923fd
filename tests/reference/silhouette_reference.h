#pragma once
// The CPU reference of the `silhouette` technique (Nagy–Klein OPS). It plans the same slices
// and samples the same positions as the GL path (slice_sampler.h), so results can be compared
// pixel by pixel.
#include "reference_frame.h"

namespace vsil::reference {

// Nagy–Klein Table 2: the intermediate state t combined with this slice's contour value c.
// Written independently of the shader's table, as the paper states it column by column.
PixelState decide(PixelState t, PixelState c);

ReferenceFrame renderSilhouette(const Volume& volume, const RenderSettings& settings,
                                float isoEpsilon);

}  // namespace vsil::reference
