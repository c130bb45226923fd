#pragma once
// Díaz & Vázquez, VG 2010, Table 1 in shape: frames per second at 512² of MIP, DEMIP and DEMIP
// with the colour sphere on the classic datasets here, DEMIP/MIP in frame time, and the paper's
// numbers beside ours where it measured the same dataset (its Table 1 in full in the notes).
#include <optional>
#include <string>
#include <vector>

#include "harness/table.h"

namespace vsil::bench {

// The dataset names --only accepts: aneurism, bonsai, engine, teddybear, tooth.
std::vector<std::string> dv1DatasetNames();
// The file a dataset is read from (in the datasets folder), or none for an unknown name.
std::optional<std::string> dv1DatasetFile(const std::string& name);

TableResult runDv1Table(const BenchOptions& options, Progress& progress);

}  // namespace vsil::bench
