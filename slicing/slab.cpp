#include "slicing/slab.h"

#include <algorithm>
#include <glm/glm.hpp>
#include <optional>

namespace vsil {

namespace {
// The brick of layer z (the first along x and y: every brick of a layer has its z bounds).
const Brick& brickOfLayer(const BrickLayout& layout, int z) {
  const glm::ivec3 counts = layout.counts();
  return layout.bricks()[std::size_t(z) * std::size_t(counts.x) * std::size_t(counts.y)];
}
}  // namespace

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
