#pragma once
// The CPU references of `mip`, `demip` and `lmip`: each pixel's maximum over the same slice samples
// as the GL path, the window's grey; for demip the first sample within --material-eps of that
// maximum, the depth weighting with each --depth-mode, and the colour sphere — written from the
// paper's equations (papers/README.md), not from the shaders.
#include "reference_frame.h"

namespace vsil::reference {

ReferenceFrame renderMip(const Volume& volume, const RenderSettings& settings, float isoEpsilon);
ReferenceFrame renderDemip(const Volume& volume, const RenderSettings& settings, float isoEpsilon);
// `lmip`: along each ray, the first sample at or above --lmip-threshold starts a run; the first
// sample that falls below the run's highest ends it, and that highest is shown (the plain
// maximum where no sample reaches the threshold).
ReferenceFrame renderLmip(const Volume& volume, const RenderSettings& settings, float isoEpsilon);

}  // namespace vsil::reference
