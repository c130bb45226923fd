#pragma once
// The semantic table: frames per second of Rautek et al.'s fuzzy-rule rendering (technique
// `semantic`) on the 256³ Bonsai at 512² for procedural rule bases of 1, 4, 16 and 32 rules, each
// with its frame time's ratio to the plain lit composite (`illustrate --effects none`, the dv1
// table's DVR column) from the same run; and the frame after a membership-function change (no
// program compiled) against the frame after a rule change (one program compiled), both on the
// 16-rule base. Target (the issue): 16 rules ≤ 2× the plain composite's frame time.
#include <optional>
#include <string>
#include <vector>

#include "harness/table.h"

namespace vsil::bench {

// The dataset names --only accepts: bonsai (measured by default) and neghip (only when asked:
// small, for quick runs).
std::vector<std::string> semanticDatasetNames();
// The file a dataset is read from (in the datasets folder), or none for an unknown name.
std::optional<std::string> semanticDatasetFile(const std::string& name);

TableResult runSemanticTable(const BenchOptions& options, Progress& progress);

}  // namespace vsil::bench
