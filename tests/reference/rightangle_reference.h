#pragma once
// The CPU reference of the `rightangle` technique (RA): the first sample at or above the iso
// value along each pixel's ray, on the same slices as the GL path; the line test at that hit.
#include "reference_frame.h"

namespace vsil::reference {

ReferenceFrame renderRightAngle(const Volume& volume, const RenderSettings& settings,
                                float isoEpsilon);

}  // namespace vsil::reference
