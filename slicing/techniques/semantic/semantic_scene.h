#pragma once
// What technique `semantic` makes of its options before any GL work, shared with its CPU
// reference (tests/reference/semantic_frame_reference.h): the rule base (--rules, a preset or a
// file), its generated code, the tables, the sphere atlas, the layer order, and the interaction
// inputs — the cursor (voxel coordinates; its pixel), the plane, the time, the global flatness.
//
// Sources, each normalized to [0, 1] (core/rules.h AttributeSource):
//   data             (value − min) / (max − min) of the volume's value range
//   gradient         |∇f| / max |∇f| (the gradient texture's magnitude)
//   cursor_distance  |p − cursor| / |dims·spacing|, p and cursor in voxel coordinates × spacing
//   plane_distance   |(p − P)·n| / |dims·spacing|, n the unit normal in the same physical axes
//   image_distance   |pixel − cursor pixel| / |image size| (pixel centres)
//   view_angle       acos(∇f/|∇f| · viewing direction) / π: 0 where a denser region's surface
//                    faces the viewer, 0.5 edge-on and where ∇f vanishes, 1 facing away
//   time             --time
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/camera.h"
#include "core/options.h"
#include "core/rules.h"
#include "core/volume.h"
#include "slicing/techniques/semantic/rule_compiler.h"
#include "slicing/techniques/semantic/sphere_atlas.h"

namespace vsil {

const std::vector<OptionSpec>& semanticOptions();

// The options' interaction inputs, resolved for a volume and view.
struct SemanticInteraction {
  glm::dvec3 cursorVoxel{0.0};      // --cursor, default the volume's centre
  glm::dvec2 cursorPixel{0.0};      // --cursor-pixel (top-left origin), default the cursor's pixel
  glm::dvec3 planePointVoxel{0.0};  // --plane, default through the centre, normal z
  glm::dvec3 planeNormal{0.0, 0.0, 1.0};  // unit
  bool planeShow = false;
  std::optional<double> flatness;  // --flatness; unset: the flatness rules' (0 without them)
  double time = 0.0;
};
SemanticInteraction resolveSemanticInteraction(const OptionReader& options, glm::ivec3 dims,
                                               const View& view);

// The rule base --rules names (a preset, "default" when not given).
RuleBase loadSemanticRules(const OptionReader& options);

// The data values the `data` source's [0, 1] spans. The default rule base (`default.rules`) sees
// the values from Otsu's threshold (the default --iso) to core/transfer_function.h's
// defaultClassificationTop (the default MIP window's top; values beyond read 1), so its
// materials lie above the air and noise of a CT, which read 0 (no membership: transparent), and
// a few bright voxels (a nucleus) do not squeeze the rest towards 0; a rule base given by name
// or file sees the whole value range, as its author wrote it for.
ValueRange semanticDataDomain(const OptionReader& options, ValueRange range);

// Styles bottom to top: by priority, equal priorities in declaration order.
std::vector<int> styleLayerOrder(const RuleBase& rules);

// Whether frames use the flat rendering mode: --flatness given, or some rule sets the flatness.
bool usesFlatMode(const RuleBase& rules, const SemanticInteraction& interaction);

}  // namespace vsil
