#pragma once
// scaling: `mpirun -np N vsil render` (issue 35) against N = 1, 2, 3, 4 for a volume larger than
// one rank's --max-memory (gen:spheres:256 under 90 % of what one process needs: 140 MiB for
// mip): N = 1 is refused ("over --max-memory", the point of splitting), the ranks split it into
// slabs along z. Per N: the
// frame (the slowest rank's, program builds excluded), its speed-up against one process
// without the limit, the reduction's share of the frame (the combine step: MPI calls, waits,
// read-backs) and each rank's memory (its slab's samples and textures, its peak resident set).
// Each run is one mpirun child; the frame is the median over --frames runs. On a machine with
// fewer cores than ranks the ranks are oversubscribed: ratios matter, not absolute times.
// Self-check: every N >= 2 renders, and its PNG is the single process's bytes.
#include <string>
#include <vector>

#include "harness/table.h"

namespace vsil::bench {

// The technique names --only accepts (every technique; mip by default).
std::vector<std::string> scalingTechniqueNames();

// `vsil bench --table scaling`: --only the techniques (default mip), --sizes the window (256),
// --frames mpirun runs per N (default 10 is lowered to 3).
TableResult runScalingTable(const BenchOptions& options, Progress& progress);

}  // namespace vsil::bench
