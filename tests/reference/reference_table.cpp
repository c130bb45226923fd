#include "reference_table.h"

#include <stdexcept>

#include "firsthit_reference.h"
#include "illustrate_reference.h"
#include "rightangle_reference.h"
#include "silhouette_reference.h"

namespace vsil::reference {

const std::vector<ReferenceTechnique>& referenceTable() {
  static const std::vector<ReferenceTechnique> table{
      {"silhouette", renderSilhouette},
      {"rightangle", renderRightAngle},
      {"firsthit", renderFirstHit},
      // Colours are floats in [0, 1] composited in float by both; 2/255 covers early ray
      // termination (at most 1/255 per channel) and trilinear weights computed in a different
      // order, and is below what a wrong formula or a misplaced sample changes.
      {"illustrate", renderIllustrate, 2.0f / 255.0f},
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
