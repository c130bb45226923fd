#include "slicing/slab.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <glm/glm.hpp>
#include <optional>
#include <string>

#include "slicing/technique_table.h"

namespace vsil {

const Brick& brickOfLayer(const BrickLayout& layout, int z) {
  const glm::ivec3 counts = layout.counts();
  return layout.bricks()[std::size_t(z) * std::size_t(counts.x) * std::size_t(counts.y)];
}

int layerVoxelZ(const BrickLayout& layout, int layer, bool high, int dimsZ) {
  const Brick& brick = brickOfLayer(layout, layer);
  return int(std::ceil(std::clamp(high ? brick.high.z : brick.low.z, 0.0, double(dimsZ))));
}

std::array<int, 2> layersVoxels(const BrickLayout& layout, int z0, int z1, int dimsZ) {
  return {layerVoxelZ(layout, z0, false, dimsZ), layerVoxelZ(layout, z1 - 1, true, dimsZ)};
}

composition::NkRun runOf(const PairPixel& pixel) {
  composition::NkRun run;
  if (pixel.first >= 0) run.first = PixelState(pixel.first);
  run.t = PixelState(pixel.t);
  run.hit = pixel.hit;
  run.detectPrev = pixel.detectPrev;
  run.last = pixel.last;
  return run;
}

namespace {
PairPixel withRun(PairPixel pixel, const composition::NkRun& run) {
  pixel.first = run.first ? std::int32_t(*run.first) : -1;
  pixel.t = std::int32_t(run.t);
  pixel.hit = run.hit;
  pixel.detectPrev = run.detectPrev;
  pixel.last = run.last;
  return pixel;
}

PairPixel inRayOrder(const PairPixel& front, const PairPixel& back) {
  composition::NkRun run = runOf(front);
  if (front.lastSlice >= 0 && back.firstSlice > front.lastSlice + 1) {
    // Slices between the runs sample outside the volume (or nowhere): one EMPTY sample stands
    // for them (any number of EMPTY samples folds alike).
    const composition::NkSample gap{PixelState::Empty, front.last};
    run = composition::combine(run, composition::foldNk({&gap, 1}));
  }
  run = composition::combine(run, runOf(back));
  PairPixel out = withRun(front, run);
  // The hit's eye distance and shade come from the run that holds the hit: the front's unless
  // its state is EMPTY (composition::combine takes the back's hit then).
  if (front.first < 0 || PixelState(front.t) == PixelState::Empty) {
    out.eyeDistance = back.eyeDistance;
    out.shade = back.shade;
  }
  out.firstSlice = front.firstSlice >= 0 ? front.firstSlice : back.firstSlice;
  out.lastSlice = back.lastSlice >= 0 ? back.lastSlice : front.lastSlice;
  return out;
}
}  // namespace

PairPixel combineInZOrder(const PairPixel& lowerZ, const PairPixel& higherZ) {
  // Rays running towards lower z meet the higher slab first.
  return lowerZ.zDirection < 0 ? inRayOrder(higherZ, lowerZ) : inRayOrder(lowerZ, higherZ);
}

namespace {
// The test hook (slab.h techniqueGhostVoxels): the width VSIL_SLAB_GHOST_VOXELS forces, if set.
std::optional<int> ghostVoxelsForcedByTest() {
  const char* forced = std::getenv("VSIL_SLAB_GHOST_VOXELS");
  if (forced == nullptr) return std::nullopt;
  return std::atoi(forced);
}
}  // namespace

int techniqueGhostVoxels(const TechniqueInfo& technique, const OptionValues& given,
                         const View& view, glm::ivec3 dims) {
  if (const std::optional<int> forced = ghostVoxelsForcedByTest()) return *forced;
  if (!technique.slabGhostVoxels) return 0;
  return technique.slabGhostVoxels(OptionReader(technique.options, given, {}), view, dims);
}

double pixelFootprintVoxelsZ(const View& view, glm::ivec3 dims) {
  // Points of one slice plane at eye distance d for neighbouring pixels differ by d times a
  // fixed vector (perspective; orthographic: by a fixed vector): the farthest box corner
  // bounds the reach.
  const glm::dmat4 voxelFromEye = glm::inverse(view.eyeFromVoxel);
  double farthest = 0;
  for (int corner = 0; corner < 8; ++corner) {
    const glm::dvec3 p((corner & 1) ? dims.x - 0.5 : -0.5, (corner & 2) ? dims.y - 0.5 : -0.5,
                       (corner & 4) ? dims.z - 0.5 : -0.5);
    farthest = std::max(farthest, -(view.eyeFromVoxel * glm::dvec4(p, 1.0)).z);
  }
  const glm::dvec2 centre = glm::dvec2(view.viewport) * 0.5;
  const auto voxelZ = [&](glm::dvec2 pixel) {
    return (voxelFromEye * glm::dvec4(view.eyeAtNdc(view.ndcFromPixel(pixel), farthest), 1.0)).z;
  };
  double reach = 0;
  for (const glm::dvec2 step : {glm::dvec2(1, 1), glm::dvec2(1, -1)}) {
    reach = std::max(reach, std::abs(voxelZ(centre + step) - voxelZ(centre)));
  }
  return reach;
}

int rayZDirection(const View& view, glm::dvec2 pixel) {
  const glm::dvec2 ndc = view.ndcFromPixel(pixel);
  const glm::dvec3 eyeDirection = view.eyeAtNdc(ndc, 1.0) - view.eyeAtNdc(ndc, 0.0);
  const double z = (glm::inverse(view.eyeFromVoxel) * glm::dvec4(eyeDirection, 0.0)).z;
  return z > 0.0 ? 1 : z < 0.0 ? -1 : 0;
}

std::optional<int> frameZDirection(const View& view) {
  const glm::dvec2 last = glm::dvec2(view.viewport) - 0.5;
  int up = 0, down = 0;
  for (const glm::dvec2 corner :
       {glm::dvec2(0.5), glm::dvec2(last.x, 0.5), glm::dvec2(0.5, last.y), last}) {
    const int direction = rayZDirection(view, corner);
    up += direction > 0;
    down += direction < 0;
  }
  if (up > 0 && down > 0) return std::nullopt;
  return up > 0 ? 1 : down > 0 ? -1 : 0;
}

double SlabPart::ownedLowZ() const {
  return brickOfLayer(layout, ownedZ0).low.z;
}

double SlabPart::ownedHighZ() const {
  return brickOfLayer(layout, ownedZ1 - 1).high.z;
}

std::array<int, 2> SlabPart::ownedVoxels() const {
  return layersVoxels(layout, ownedZ0, ownedZ1, dims.z);
}

std::array<int, 2> SlabPart::heldVoxels() const {
  return layersVoxels(layout, heldZ0, heldZ1, dims.z);
}

int SlabPart::ghostVoxels() const {
  // How far the held voxels reach beyond the owned ones (cut to the volume) on each side that
  // has ghost layers; the thinner side.
  std::optional<int> thinnest;
  const auto reach = [&](double from, double to) {
    thinnest = std::min(thinnest.value_or(int(to - from)), int(to - from));
  };
  if (heldZ0 < ownedZ0) reach(std::max(brickOfLayer(layout, heldZ0).low.z, -0.5), ownedLowZ());
  if (heldZ1 > ownedZ1) {
    reach(ownedHighZ(), std::min(brickOfLayer(layout, heldZ1 - 1).high.z, dims.z - 0.5));
  }
  return thinnest.value_or(0);
}

}  // namespace vsil
