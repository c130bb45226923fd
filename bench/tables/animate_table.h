#pragma once
// animate: what one render job saves over separate processes. A 36-frame orbit rendered by one
// `vsil animate` process against the same 36 views rendered by 36 `vsil render` processes (each
// making its GL context, reading and uploading the volume and building its programs anew),
// wall-clock, with the ratio; the self-check compares every frame of the two paths pixel by
// pixel. Runs the vsil binary it is part of (/proc/self/exe).
#include <string>
#include <vector>

#include "harness/table.h"

namespace vsil::bench {

// The dataset names --only accepts: bonsai (the default), neghip (small, for quick runs).
std::vector<std::string> animateDatasetNames();

// `vsil bench --table animate`: --sizes replaces the window size (512), --only the datasets.
TableResult runAnimateTable(const BenchOptions& options, Progress& progress);

}  // namespace vsil::bench
