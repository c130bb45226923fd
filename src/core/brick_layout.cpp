#include "core/brick_layout.h"

#include <algorithm>
#include <array>
#include <stdexcept>

namespace vsil {

namespace {

constexpr int kV = BrickLayout::kOverlap;
constexpr double kUnbounded = 1e30;
constexpr int kMinStorage = 8;

// One axis of a layout: per brick its origin, texture size and owned sample positions.
struct AxisBricks {
  std::vector<int> origin, size;
  std::vector<double> low, high;
  std::int64_t texels() const {
    std::int64_t sum = 0;
    for (int s : size) sum += s;
    return sum;
  }
  int largest() const { return *std::max_element(size.begin(), size.end()); }
};

// Bricks of texture size `storage` along an axis of `dim` voxels (one brick, padded to a power
// of two, when that is no larger).
AxisBricks axisBricks(int dim, int storage) {
  AxisBricks axis;
  if (nextPowerOfTwo(dim) <= storage) {
    axis.origin = {0};
    axis.size = {nextPowerOfTwo(dim)};
    axis.low = {-kUnbounded};
    axis.high = {kUnbounded};
    return axis;
  }
  const int valid = storage - 2 * kV;
  const int count = (dim + valid - 1) / valid;
  for (int i = 0; i < count; ++i) {
    const int origin = std::max(0, i * valid - kV);
    const int end = std::min(dim, (i + 1) * valid + kV);  // voxels it must hold
    axis.origin.push_back(origin);
    axis.size.push_back(i + 1 < count ? storage : nextPowerOfTwo(end - origin));
    axis.low.push_back(i == 0 ? -kUnbounded : i * valid - 0.5);
    axis.high.push_back(i + 1 == count ? kUnbounded : (i + 1) * valid - 0.5);
  }
  return axis;
}

BrickLayout fromAxes(glm::ivec3 dims, const std::array<AxisBricks, 3>& axes);

}  // namespace

int nextPowerOfTwo(int n) {
  int p = 1;
  while (p < n) p *= 2;
  return p;
}

BrickLayout BrickLayout::withStorage(glm::ivec3 dims, glm::ivec3 storage) {
  for (int a = 0; a < 3; ++a) {
    if (storage[a] <= 2 * kOverlap || nextPowerOfTwo(storage[a]) != storage[a] || dims[a] < 1) {
      throw std::invalid_argument("BrickLayout: brick storage must be a power of two above 4");
    }
  }
  return fromAxes(dims, {axisBricks(dims.x, storage.x), axisBricks(dims.y, storage.y),
                         axisBricks(dims.z, storage.z)});
}

BrickLayout BrickLayout::choose(glm::ivec3 dims, std::size_t texelBytes,
                                std::uint64_t maxTextureBytes, int maxTextureSide) {
  const std::uint64_t maxTexels = maxTextureBytes / std::max<std::size_t>(texelBytes, 1);
  const glm::ivec3 whole(nextPowerOfTwo(dims.x), nextPowerOfTwo(dims.y), nextPowerOfTwo(dims.z));
  if (glm::all(glm::lessThanEqual(whole, glm::ivec3(maxTextureSide))) &&
      std::uint64_t(whole.x) * whole.y * whole.z <= maxTexels) {
    return withStorage(dims, whole);
  }
  // Each brick costs a draw call per slice piece: counted as this many texels.
  constexpr double kTexelsPerBrick = 1 << 16;
  std::array<std::vector<AxisBricks>, 3> options;
  for (int a = 0; a < 3; ++a) {
    for (int s = kMinStorage; s <= std::max(kMinStorage, maxTextureSide); s *= 2) {
      options[a].push_back(axisBricks(dims[a], s));
      if (s >= whole[a]) break;
    }
  }
  const AxisBricks* best[3] = {nullptr, nullptr, nullptr};
  double bestCost = 0;
  for (const auto& x : options[0]) {
    for (const auto& y : options[1]) {
      for (const auto& z : options[2]) {
        if (std::uint64_t(x.largest()) * y.largest() * z.largest() > maxTexels) continue;
        const double bricks = double(x.size.size() * y.size.size() * z.size.size());
        const double cost =
            double(x.texels()) * double(y.texels()) * double(z.texels()) + bricks * kTexelsPerBrick;
        if (!best[0] || cost < bestCost) {
          best[0] = &x, best[1] = &y, best[2] = &z;
          bestCost = cost;
        }
      }
    }
  }
  if (!best[0]) {
    throw std::invalid_argument("BrickLayout: not even an 8x8x8 brick fits the texture limit");
  }
  return fromAxes(dims, {*best[0], *best[1], *best[2]});
}

namespace {

BrickLayout fromAxes(glm::ivec3 dims, const std::array<AxisBricks, 3>& axes) {
  std::vector<Brick> bricks;
  const glm::ivec3 counts(int(axes[0].size.size()), int(axes[1].size.size()),
                          int(axes[2].size.size()));
  for (int k = 0; k < counts.z; ++k) {
    for (int j = 0; j < counts.y; ++j) {
      for (int i = 0; i < counts.x; ++i) {
        const glm::ivec3 index(i, j, k);
        Brick brick;
        brick.index = index;
        for (int a = 0; a < 3; ++a) {
          const auto n = std::size_t(index[a]);
          brick.origin[a] = axes[std::size_t(a)].origin[n];
          brick.size[a] = axes[std::size_t(a)].size[n];
          brick.low[a] = axes[std::size_t(a)].low[n];
          brick.high[a] = axes[std::size_t(a)].high[n];
        }
        bricks.push_back(brick);
      }
    }
  }
  return BrickLayout(dims, counts, std::move(bricks));
}

}  // namespace

std::uint64_t BrickLayout::texels() const {
  std::uint64_t sum = 0;
  for (const Brick& b : bricks_) sum += std::uint64_t(b.size.x) * b.size.y * b.size.z;
  return sum;
}

std::uint64_t BrickLayout::largestTexels() const {
  std::uint64_t largest = 0;
  for (const Brick& b : bricks_) {
    largest = std::max(largest, std::uint64_t(b.size.x) * b.size.y * b.size.z);
  }
  return largest;
}

}  // namespace vsil
