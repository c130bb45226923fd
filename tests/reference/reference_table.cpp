#include "reference_table.h"

#include <stdexcept>

#include "firsthit_reference.h"
#include "rightangle_reference.h"
#include "silhouette_reference.h"

namespace vsil::reference {

const std::vector<ReferenceTechnique>& referenceTable() {
  static const std::vector<ReferenceTechnique> table{
      {"silhouette", renderSilhouette},
      {"rightangle", renderRightAngle},
      {"firsthit", renderFirstHit},
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
