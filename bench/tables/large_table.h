#pragma once
// large: volumes larger than one 3D texture (core/brick_layout.h). A procedurally written uint8
// volume of 512³ (the reference), 1024³ and 2048×2048×1024 (4 GiB), each written to a temporary
// raw file once and removed after, rendered by one `vsil animate` process (silhouette, a few
// frames of a small orbit): load + upload seconds (its set-up), the silhouette frame time (the
// median of the frames after the first, which compiles the programs), the bricks, and the
// process's peak resident memory (wait4), per voxel. Targets: every volume renders; the 1024³
// frame costs at most 3× the 512³ frame; peak memory at most 3.5 bytes per voxel.
#include <string>
#include <vector>

#include "harness/table.h"

namespace vsil::bench {

// The volume names --only accepts: 512, 1024, 2048 (all three by default).
std::vector<std::string> largeDatasetNames();

// `vsil bench --table large`: --sizes replaces the window size (512), --frames the timed frames
// (default 10 is lowered to 3: each frame of the largest volume takes a while).
TableResult runLargeTable(const BenchOptions& options, Progress& progress);

}  // namespace vsil::bench
