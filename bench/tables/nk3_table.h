#pragma once
// Nagy–Klein, WSCG 2004, Table 3: frames per second of the right-angle baseline (RA), the
// one-pixel silhouettes (OPS) and the broadened silhouettes (BS = OPS + FFT broadening +
// composition), for the paper's datasets at 256² and 512², with the paper's numbers beside ours.
#include <optional>
#include <string>
#include <vector>

#include "harness/table.h"

namespace vsil::bench {

// The dataset names --only accepts: bonsai, engine, hydrogen_atom, neghip, skull, teddybear.
std::vector<std::string> nk3DatasetNames();

// A dataset of Table 3 as other tables render it: its file in the datasets folder and the iso
// value chosen for it, with the reason. Nothing for an unknown name or one without a stored copy.
struct Nk3DatasetFile {
  std::string file;
  double iso = 0;
  std::string isoReason;
};
std::optional<Nk3DatasetFile> nk3DatasetFile(const std::string& name);

TableResult runNk3Table(const BenchOptions& options, Progress& progress);

}  // namespace vsil::bench
