#pragma once
// The CPU reference of the `illustrate` technique (slicing/techniques/illustrate/): every pixel's
// samples on the same slices as the GL path, classified, enhanced by the effects the options
// switch on (the Ebert–Rheingans formulas written again here, independently of
// shaders/illustration.glsl) and composited front to back with the opacity correction of
// shaders/compositing.glsl. No early ray termination and no empty-space skipping: the GL path's
// skipping may change a channel by at most 1/255, which the comparison's tolerance covers.
#include "reference_frame.h"

namespace vsil::reference {

ReferenceFrame renderIllustrate(const Volume& volume, const RenderSettings& settings,
                                float isoEpsilon);

}  // namespace vsil::reference
