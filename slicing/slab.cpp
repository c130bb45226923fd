#include "slicing/slab.h"

#include <algorithm>
#include <optional>

namespace vsil {

namespace {
// The brick of layer z (the first along x and y: every brick of a layer has its z bounds).
const Brick& brickOfLayer(const BrickLayout& layout, int z) {
  const glm::ivec3 counts = layout.counts();
  return layout.bricks()[std::size_t(z) * std::size_t(counts.x) * std::size_t(counts.y)];
}
}  // namespace

double SlabPart::ownedLowZ() const {
  return brickOfLayer(layout, ownedZ0).low.z;
}

double SlabPart::ownedHighZ() const {
  return brickOfLayer(layout, ownedZ1 - 1).high.z;
}

int SlabPart::ghostVoxels() const {
  // A ghost layer's own voxels (its owned range, cut to the volume) on each side held.
  std::optional<int> thinnest;
  for (int z = heldZ0; z < heldZ1; ++z) {
    if (z >= ownedZ0 && z < ownedZ1) continue;
    const Brick& brick = brickOfLayer(layout, z);
    const double low = std::max(brick.low.z, -0.5), high = std::min(brick.high.z, dims.z - 0.5);
    thinnest = std::min(thinnest.value_or(int(high - low)), int(high - low));
  }
  return thinnest.value_or(0);
}

}  // namespace vsil
