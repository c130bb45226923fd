// The silhouette pair across slabs (slicing/slab.h combineInZOrder): every pixel's runs, folded
// per slab from what a slab sees (its samples inside the volume, slices numbered), combined in
// z order with the pixel's direction, give the sequential fold of the whole ray, extra empty
// slice included. Rays start and end outside the volume (samples no slab draws, EMPTY).
#include <gtest/gtest.h>

#include <vector>

#include "core/composition.h"
#include "slicing/slab.h"

namespace vsil {
namespace {

using composition::NkRun;
using composition::NkSample;

struct RaySample {
  NkSample sample;
  bool inside = true;  // drawn by a slab; outside the volume it is EMPTY and drawn by none
  int slice = 0;
};

// What one slab's process makes of its samples (silhouette_technique.cpp pairPixel): the fold
// of those it draws, the first of them as the first value, their slice span.
PairPixel slabPixel(const std::vector<RaySample>& run, int zDirection) {
  std::vector<NkSample> drawn;
  PairPixel pixel;
  pixel.zDirection = zDirection;
  for (const RaySample& s : run) {
    if (!s.inside) continue;
    if (drawn.empty()) pixel.firstSlice = s.slice;
    pixel.lastSlice = s.slice;
    drawn.push_back(s.sample);
  }
  if (drawn.empty()) return pixel;
  const NkRun folded = composition::foldNk(drawn);
  pixel.first = std::int32_t(*folded.first);
  pixel.t = std::int32_t(folded.t);
  pixel.hit = folded.hit;
  pixel.detectPrev = folded.detectPrev;
  pixel.last = folded.last;
  pixel.eyeDistance = pixel.shade = 10.0f + folded.hit;  // travel with the hit
  return pixel;
}

NkRun finished(NkRun run) {
  const NkSample emptySlice{PixelState::Empty, 1.0f};
  return composition::combine(run, composition::foldNk({&emptySlice, 1}));
}

TEST(SlabPair, CombinedInZOrderEqualsTheWholeRay) {
  const PixelState values[3] = {PixelState::Empty, PixelState::Filled, PixelState::Contour};
  int cases = 0;
  for (int inner = 0; inner <= 5; ++inner) {
    int combos = 1;
    for (int i = 0; i < inner; ++i) combos *= 3;
    for (int code = 0; code < combos; ++code) {
      for (int before = 0; before <= 2; ++before) {
        for (int after = 0; after <= 2; ++after) {
          std::vector<RaySample> ray;
          int c = code;
          for (int i = 0; i < before + inner + after; ++i) {
            const bool inside = i >= before && i < before + inner;
            RaySample s;
            s.inside = inside;
            s.slice = i;
            s.sample = {inside ? values[c % 3] : PixelState::Empty, 0.1f * float(i + 1)};
            if (inside) c /= 3;
            ray.push_back(s);
          }
          std::vector<NkSample> all;
          for (const RaySample& s : ray) all.push_back(s.sample);
          const NkRun whole = finished(composition::foldNk(all));
          const int n = int(ray.size());
          for (int a = 0; a <= n; ++a) {
            for (int b = a; b <= n; ++b) {
              const std::vector<RaySample> front(ray.begin(), ray.begin() + a);
              const std::vector<RaySample> middle(ray.begin() + a, ray.begin() + b);
              const std::vector<RaySample> back(ray.begin() + b, ray.end());
              for (const int direction : {1, -1}) {
                // Lower z first: the ray's front for direction +1, its back for -1.
                std::vector<PairPixel> zOrder{slabPixel(front, direction),
                                              slabPixel(middle, direction),
                                              slabPixel(back, direction)};
                if (direction < 0) std::swap(zOrder[0], zOrder[2]);
                // Both groupings: MPI_Reduce may combine in either.
                const PairPixel left =
                    combineInZOrder(combineInZOrder(zOrder[0], zOrder[1]), zOrder[2]);
                const PairPixel right =
                    combineInZOrder(zOrder[0], combineInZOrder(zOrder[1], zOrder[2]));
                for (const PairPixel& combined : {left, right}) {
                  const NkRun run = finished(runOf(combined));
                  ASSERT_EQ(run.t, whole.t) << "case " << cases;
                  if (run.t == PixelState::Empty) continue;
                  ASSERT_EQ(run.depth(), whole.depth()) << "case " << cases;
                  ASSERT_EQ(combined.eyeDistance, 10.0f + whole.hit) << "case " << cases;
                }
                ++cases;
              }
            }
          }
        }
      }
    }
  }
  EXPECT_GT(cases, 10000);
}

}  // namespace
}  // namespace vsil
