#pragma once
// The CPU reference of each technique, by the technique's name, so that the GL-vs-reference
// tests run over a table instead of comparing names. A technique joins with one entry.
#include <functional>
#include <string>
#include <vector>

#include "reference_frame.h"

namespace vsil::reference {

using ReferenceRenderer = std::function<ReferenceFrame(
    const Volume& volume, const RenderSettings& settings, float isoEpsilon)>;

struct ReferenceTechnique {
  std::string technique;  // its name in slicing/technique_table.h
  ReferenceRenderer render;
  // Colour techniques: the largest difference per channel (premultiplied RGBA in [0, 1]) GL
  // may show against the reference away from ambiguous pixels, with its reason.
  float colorTolerance = 0.0f;
  // Options every GL-vs-reference case sets, beside the scene's iso value and each choice
  // option's values (e.g. an effect that is off by default).
  OptionValues caseOptions;
  // The share of the pixels shown (the line pixels where a technique draws lines) that may
  // differ where the reference marks them ambiguous, with its reason.
  double ambiguousShare = 0.01;
};

const std::vector<ReferenceTechnique>& referenceTable();
// The entry for `technique`; throws std::out_of_range when it has none.
const ReferenceTechnique& findReference(const std::string& technique);

}  // namespace vsil::reference
