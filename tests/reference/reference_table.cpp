#include "reference_table.h"

#include <stdexcept>

#include "firsthit_reference.h"
#include "illustrate_reference.h"
#include "mip_reference.h"
#include "rightangle_reference.h"
#include "semantic_frame_reference.h"
#include "silhouette_reference.h"

namespace vsil::reference {

namespace {

OptionValues toneFillCaseOptions() {
  return {{"param", std::vector<std::string>{"k_ty=0.45,k_tb=0.2,k_td=0.5", "k_ds=0.6,k_de=0.8"}},
          {"light", std::vector<std::string>{"30,40", "-60,10"}}};
}

}  // namespace

const std::vector<ReferenceTechnique>& referenceTable() {
  static const std::vector<ReferenceTechnique> table{
      // The state techniques' cases tone-fill (gl_vs_reference_test.cpp), with parameters
      // and two lights other than the defaults, so that they reach the fill too.
      {"silhouette", renderSilhouette, 0.0f, toneFillCaseOptions()},
      {"rightangle", renderRightAngle, 0.0f, toneFillCaseOptions()},
      {"firsthit", renderFirstHit, 0.0f, {}},
      // Greys are quotients of floats (the window), depths of the box entry come from float
      // ray-box slabs: rounding only, far below one 8-bit step (0.004). The default window
      // (Otsu's threshold to a high percentile) is narrower than the value range, and the
      // quotient scales the samples' rounding by range / width (up to about 4 here): 5e-4.
      {"mip", renderMip, 5e-4f, {}},
      // Every case tints with the colour sphere, so that it is compared too.
      {"demip", renderDemip, 5e-4f, {{"sphere-weight", 0.4}}},
      // LMIP on 8-bit data meets plateaus, where consecutive samples tie and float rounding
      // decides whether a run ends there (neghip: 2.7 % of the pixels; every one flagged). With
      // the default threshold at the window's low end, a ray whose first run starts within
      // rounding of the threshold is shown (grey near 0) by one and not by the other (neghip:
      // 8.7 %; every one flagged).
      {"lmip", renderLmip, 5e-4f, {}, 0.1},
      // Colours are floats in [0, 1] composited in float by both; 2/255 covers early ray
      // termination (at most 1/255 per channel) and trilinear weights computed in a different
      // order, and is below what a wrong formula or a misplaced sample changes.
      {"illustrate", renderIllustrate, 2.0f / 255.0f, {}},
      // As illustrate: float colours composited in float, early ray termination (<= 1/255) and
      // trilinear weights (volume, gradients, sphere atlas) rounded in a different order.
      {"semantic", renderSemantic, 2.0f / 255.0f, {}},
  };
  return table;
}

const ReferenceTechnique& findReference(const std::string& technique) {
  for (const auto& entry : referenceTable()) {
    if (entry.technique == technique) return entry;
  }
  throw std::out_of_range("no CPU reference for technique '" + technique + "'");
}

}  // namespace vsil::reference
