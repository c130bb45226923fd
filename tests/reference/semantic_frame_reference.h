#pragma once
// The CPU reference of technique `semantic` (slicing/techniques/semantic/): every pixel's samples
// on the same slices as the GL path, the sources normalized as semantic_scene.h says, the rules
// evaluated from the same membership and defuzzification tables read as the shader reads them
// (two entries mixed; the fuzzy pipeline itself against the paper's direct integration is
// semantic_reference.h's, checked in tests/core), the styles' spheres sampled trilinearly from
// the same atlas texels, layered by priority and composited front to back (in flat mode with
// c_r·(1 − p_f) on entering a higher priority). Written from the formulas, not from the GLSL:
// the rule tree is walked here, not compiled. No early ray termination and no empty-space
// skipping (at most 1/255 per channel, covered by the comparison's tolerance).
//
// Ambiguous pixels (flat mode): where along the ray a sample's region (the style giving it the
// most opacity) is decided by less than kRegionEpsilon between styles of different priority,
// float rounding may pick the other region in GL.
#include "reference_frame.h"

namespace vsil::reference {

inline constexpr float kRegionEpsilon = 1e-4f;

ReferenceFrame renderSemantic(const Volume& volume, const RenderSettings& settings,
                              float isoEpsilon);

}  // namespace vsil::reference
