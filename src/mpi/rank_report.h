#pragma once
// Every rank's share of `mpirun -np N vsil render` for --meta-out (issue 35): how long its frame
// took, how much of it went to its slab and how much to combining with the others, and the
// memory it held. Built only with VSIL_HAVE_MPI.
#include <cstdint>

#include <nlohmann/json.hpp>

#include "slicing/slab.h"

namespace vsil::mpi {

struct RankNumbers {
  double frameMs = 0;  // RenderJob::render, less program builds: slab, combining, read-back, post
  double frameCpuMs = 0;  // the same in the process's CPU time (every thread): robust to load
  double renderMs = 0;    // slicing its slab (RenderTimings::render)
  double reduceMs = 0;    // combining with the other ranks (RenderTimings::combine)
  double heldBytes = 0;   // its slab's samples plus the volume textures of its bricks
  double peakResidentBytes = 0;  // the process's peak resident set (getrusage's ru_maxrss)
  double checkedBytes = 0;       // what the --max-memory check counted for its slab (an estimate)
};

// The bytes of the volume textures `part` holds (its own and its ghost bricks, padded storage).
std::uint64_t heldTextureBytes(const SlabPart& part);

// This process's peak resident set in bytes so far.
double peakResidentBytes();

// On rank 0: every rank's numbers, in rank order, as objects {"rank", "frame_ms", "frame_cpu_ms",
// "render_ms", "reduce_ms", "held_bytes", "peak_rss_bytes", "checked_bytes"}; an empty array
// elsewhere. A collective: every rank calls it.
nlohmann::json gatherRankNumbers(const RankNumbers& mine);

}  // namespace vsil::mpi
