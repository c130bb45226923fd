#pragma once
// The illustrate table: frames per second of Ebert–Rheingans volume illustration on the 256³
// Bonsai and the Engine at 512²: the plain lit composite, each effect alone and all together,
// each row with its frame time's ratio to the plain composite's, and the right-angle baseline
// (RA, rightangle at the nk3 iso value) from the same run. Targets (the issue): each effect
// ≤ 1.3× the plain frame time (halos ≤ 1.6×), all together ≤ 2×, the plain composite ≤ 1.5× RA.
#include <optional>
#include <string>
#include <vector>

#include "harness/table.h"

namespace vsil::bench {

// The dataset names --only accepts: bonsai, engine (measured by default) and neghip (only
// when asked: small, for quick runs).
std::vector<std::string> illustrateDatasetNames();
// The file a dataset is read from (in the datasets folder), or none for an unknown name.
std::optional<std::string> illustrateDatasetFile(const std::string& name);

TableResult runIllustrateTable(const BenchOptions& options, Progress& progress);

}  // namespace vsil::bench
