#pragma once
// Nagy–Klein, WSCG 2004, Table 3: frames per second of the right-angle baseline (RA), the
// one-pixel silhouettes (OPS) and the broadened silhouettes (BS = OPS + FFT broadening +
// composition), for the paper's datasets at 256² and 512², with the paper's numbers beside ours.
#include <string>
#include <vector>

#include "harness/table.h"

namespace vsil::bench {

// The dataset names --only accepts: bonsai, engine, hydrogen_atom, neghip, skull, teddybear.
std::vector<std::string> nk3DatasetNames();

TableResult runNk3Table(const BenchOptions& options, Progress& progress);

}  // namespace vsil::bench
