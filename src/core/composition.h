#pragma once
// How partial results of one frame combine when the samples of each ray are split into runs
// (the slabs of `mpirun -np N vsil render`, issue 35): each technique's rule, stated in its
// entry of slicing/technique_table.h and proved against the sequential fold by brute force over
// every short sequence split at every point (tests/core/composition_test.cpp). A run is the
// samples of one pixel's ray inside one slab, in the ray's order (front to back); a combine
// takes the run in front and the run behind it.
#include <cstdint>
#include <optional>
#include <span>

#include "core/frame.h"

namespace vsil {

// How a technique's partial frames combine across slabs.
enum class Composition {
  PairReduce,      // silhouette: the (first value, state) pair below; exact and associative
  MaxReduce,       // mip: the maximum and the depth of its first occurrence; exact
  LocalMaxReduce,  // lmip's run summary below; exact and associative (lmip itself relays:
                   // technique_table.cpp says why)
  Relay,           // front-to-back "over" (firsthit, rightangle, illustrate, semantic,
                   // demip's two sweeps; lmip): float over is not associative, so the
                   // accumulated image travels from slab to slab in depth order
  None,            // cannot be split
};
const char* compositionName(Composition composition);  // "pair-reduce", "max-reduce", ...

namespace composition {

// Nagy–Klein's decision table (the slice shaders' silhouette.glsl decideRecord, the CPU
// reference's decide): the record `t` meeting this slice's contour value `c`.
PixelState decide(PixelState t, PixelState c);

// One sample of a ray for silhouette: its contour value and its slice's normalized depth.
struct NkSample {
  PixelState c = PixelState::Empty;
  float depth = 0;
};
// A run of samples (consecutive slices), folded from EMPTY. `hit` is the depth of the first
// non-EMPTY record (the paper's first hit); a silhouette found by detection (CONTOUR meeting an
// EMPTY sample) lies halfway between `hit` and the sample before the detecting one
// (`detectPrev`), as silhouette.glsl places it.
struct NkRun {
  std::optional<PixelState> first;  // the first sample's c; none for a run without samples
  PixelState t = PixelState::Empty;
  float hit = 0;
  float detectPrev = 0;
  float last = 0;  // the last sample's depth
  // The record's depth: the hit, or for a detected silhouette halfway to the sample before.
  float depth() const;
};
NkRun foldNk(std::span<const NkSample> samples);
// front, then back: t_f EMPTY → back; FILLED or SILHOUETTE → front; CONTOUR → by the back's
// first value: EMPTY → SILHOUETTE (detected between the runs), FILLED → FILLED, CONTOUR → the
// back's state with the front's hit (a back run starting on CONTOUR never returns to EMPTY, so
// its depth is made from its first hit, which the front's replaces). first = first_f (none →
// first_b).
NkRun combine(const NkRun& front, const NkRun& back);

// mip: the largest value and the depth of its first occurrence (later equal values do not
// replace it, as the max blend's depth test keeps the nearest).
struct MaxRun {
  bool any = false;
  float value = 0;
  float depth = 0;
};
MaxRun foldMax(std::span<const float> values, std::span<const float> depths);
MaxRun combine(const MaxRun& front, const MaxRun& back);

// lmip (mip_reference.h renderLmip): the first sample at or above `threshold` starts a run, the
// first sample below the run's highest ends it, and that highest is shown (without a run, the
// plain maximum). A run of samples summarized: its first value, whether the local maximum is
// settled (`done`), the highest of the open or settled run (`top`), and the plain maximum.
struct LmipRun {
  bool any = false;
  float first = 0;
  bool hasTop = false;
  bool done = false;
  float top = 0, topDepth = 0;
  float max = 0;
};
LmipRun foldLmip(std::span<const float> values, std::span<const float> depths, float threshold);
// front, then back: a settled front wins; a front without a run gives the back's (the plain
// maximum of both); an open front run of highest T ends at the back's first sample when that is
// below T, else it goes on as the back's own summary, which started a run at that sample, keeping
// the front's T and its depth where the back never rose above T.
LmipRun combine(const LmipRun& front, const LmipRun& back);

}  // namespace composition
}  // namespace vsil
