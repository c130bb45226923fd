#pragma once
// The CPU reference of the `firsthit` technique: the first sample at or above the iso value along
// each pixel's ray, on the same slices as the GL path; grey 1 − d there.
#include "reference_frame.h"

namespace vsil::reference {

ReferenceFrame renderFirstHit(const Volume& volume, const RenderSettings& settings,
                              float isoEpsilon);

}  // namespace vsil::reference
