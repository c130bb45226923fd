#include "core/brick_layout.h"

#include <algorithm>
#include <array>
#include <stdexcept>

namespace vsil {

namespace {

constexpr int kV = BrickLayout::kOverlap;
constexpr double kUnbounded = 1e30;
constexpr int kMinStorage = BrickLayout::kMinStorage;

// One axis of a layout: per brick its origin, texture size and owned sample positions.
struct AxisBricks {
  std::vector<int> origin, size;
  std::vector<double> low, high;
  std::int64_t texelSum = 0;  // of size
  int largestSize = 0;
  std::int64_t texels() const { return texelSum; }
  int largest() const { return largestSize; }
  std::size_t count() const { return size.size(); }
};

// The bricks along an axis of `dim` voxels with texture sizes `sizes` (powers of two; every
// one but the last larger than 2·kV). Brick i owns the positions from its start b_i − 0.5 (b_0
// = −∞) to b_{i+1} − 0.5, b_{i+1} = b_i + size_i − 2·kV, and stores from origin_i =
// max(0, b_i − kV); the last brick's size is where its stored voxels end, as given.
AxisBricks axisFromSizes(const std::vector<int>& sizes) {
  AxisBricks axis;
  int start = 0;
  for (std::size_t i = 0; i < sizes.size(); ++i) {
    const bool last = i + 1 == sizes.size();
    axis.origin.push_back(std::max(0, start - kV));
    axis.size.push_back(sizes[i]);
    axis.low.push_back(i == 0 ? -kUnbounded : start - 0.5);
    start += sizes[i] - 2 * kV;
    axis.high.push_back(last ? kUnbounded : start - 0.5);
    axis.texelSum += sizes[i];
    axis.largestSize = std::max(axis.largestSize, sizes[i]);
  }
  return axis;
}

// The voxels from the brick that starts at `start` to the end of an axis of `dim` voxels.
int restFrom(int dim, int start) {
  return dim - std::max(0, start - kV);
}

// Bricks of size `storage` from the start of an axis of `dim` voxels while the rest does not
// fit one; `start` becomes the first position the next brick owns.
std::vector<int> fullBricks(int dim, int storage, int& start) {
  std::vector<int> sizes;
  start = 0;
  while (restFrom(dim, start) > storage) {
    sizes.push_back(storage);
    start += storage - 2 * kV;
  }
  return sizes;
}

// Bricks of texture size `storage` along an axis of `dim` voxels, the last one the smallest
// power of two that holds the rest (one brick, padded to a power of two, when that is no
// larger than `storage`).
AxisBricks axisBricks(int dim, int storage) {
  int start = 0;
  std::vector<int> sizes = fullBricks(dim, storage, start);
  sizes.push_back(nextPowerOfTwo(restFrom(dim, start)));
  return axisFromSizes(sizes);
}

// The ways to cut an axis considered by choose: for each largest size S (up to maxSide), bricks
// of S while the rest does not fit one, then a tail of smaller powers of two — the smallest
// that holds the rest, or the largest below it followed by another tail (300 with S = 256:
// 256 + 64; 400: 256 + 128 + 32 rather than 256 + 256). Pruned to the options no other beats
// in brick count, texels and largest brick at once.
std::vector<AxisBricks> axisOptions(int dim, int maxSide) {
  std::vector<std::vector<int>> sequences;
  const int whole = nextPowerOfTwo(dim);
  if (whole <= std::max(kMinStorage, maxSide)) sequences.push_back({whole});
  for (int s = kMinStorage; s <= maxSide && s < whole; s *= 2) {
    int start = 0;
    std::vector<int> sizes = fullBricks(dim, s, start);
    // The tail: at each step either end with the smallest power of two holding the rest, or
    // place the largest one below it (at least kMinStorage) and go on.
    for (;;) {
      const int rest = restFrom(dim, start);
      std::vector<int> ended = sizes;
      ended.push_back(nextPowerOfTwo(rest));
      sequences.push_back(std::move(ended));
      const int below = nextPowerOfTwo(rest) / 2;
      if (below < kMinStorage || below >= rest) break;
      sizes.push_back(below);
      start += below - 2 * kV;
    }
  }
  std::vector<AxisBricks> options;
  for (const auto& sizes : sequences) options.push_back(axisFromSizes(sizes));
  std::vector<AxisBricks> kept;
  for (std::size_t i = 0; i < options.size(); ++i) {
    const AxisBricks& a = options[i];
    bool beaten = false;
    for (std::size_t j = 0; j < options.size() && !beaten; ++j) {
      const AxisBricks& b = options[j];
      const bool noWorse =
          b.count() <= a.count() && b.texels() <= a.texels() && b.largest() <= a.largest();
      const bool better =
          b.count() < a.count() || b.texels() < a.texels() || b.largest() < a.largest();
      // Equal options: keep the first.
      beaten = noWorse && (better || j < i);
    }
    if (!beaten) kept.push_back(a);
  }
  return kept;
}

BrickLayout fromAxes(glm::ivec3 dims, const std::array<AxisBricks, 3>& axes);

// The voxels and overlap copies `count` bricks along an axis of `dim` voxels store, at least
// kSmallestCutSide (below it no cut holds an axis in fewer texels than the next power of two).
double storedSide(int dim, std::size_t count) {
  return std::max(double(BrickLayout::kSmallestCutSide), dim + 2.0 * kV * double(count - 1));
}

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
                                std::uint64_t maxTextureBytes, int maxTextureSide,
                                Bricking bricking) {
  const std::uint64_t maxTexels = maxTextureBytes / std::max<std::size_t>(texelBytes, 1);
  // At least kMinStorage along an axis: a brick holds its overlap beside its own voxels (a
  // DICOM series of 4x3x5 samples takes 8³ texels).
  const glm::ivec3 whole =
      glm::max(glm::ivec3(nextPowerOfTwo(dims.x), nextPowerOfTwo(dims.y), nextPowerOfTwo(dims.z)),
               glm::ivec3(kMinStorage));
  const std::uint64_t voxels = std::uint64_t(dims.x) * dims.y * dims.z;
  const std::uint64_t wholeTexels = std::uint64_t(whole.x) * whole.y * whole.z;
  const bool wholeFits =
      glm::all(glm::lessThanEqual(whole, glm::ivec3(maxTextureSide))) && wholeTexels <= maxTexels;
  const double wholeStored = storedSide(dims.x, 1) * storedSide(dims.y, 1) * storedSide(dims.z, 1);
  if (wholeFits &&
      (bricking == Bricking::OneIfItFits || double(wholeTexels) <= kMaxWaste * wholeStored ||
       double((wholeTexels - voxels) * texelBytes) <=
           kPaddingShareOfLimit * double(maxTextureBytes))) {
    return withStorage(dims, whole);
  }
  std::array<std::vector<AxisBricks>, 3> options;
  for (int a = 0; a < 3; ++a) {
    options[std::size_t(a)] = axisOptions(dims[a], std::max(kMinStorage, maxTextureSide));
  }
  // Among the layouts within kMaxWaste of the voxels they must store (overlap included), the
  // fewest bricks (each costs a draw per slice piece), then the fewest texels. When none is
  // (only small bricks fit), the fewest texels with a cost per brick.
  constexpr double kTexelsPerBrick = 1 << 16;
  const AxisBricks* best[3] = {nullptr, nullptr, nullptr};
  bool bestWithin = false;
  double bestBricks = 0, bestTexels = 0;
  for (const auto& x : options[0]) {
    for (const auto& y : options[1]) {
      for (const auto& z : options[2]) {
        if (std::uint64_t(x.largest()) * y.largest() * z.largest() > maxTexels) continue;
        const double bricks = double(x.count() * y.count() * z.count());
        const double texels = double(x.texels()) * double(y.texels()) * double(z.texels());
        const double stored = storedSide(dims.x, x.count()) * storedSide(dims.y, y.count()) *
                              storedSide(dims.z, z.count());
        const bool within = texels <= kMaxWaste * stored;
        bool better = false;
        if (!best[0] || within != bestWithin) {
          better = !best[0] || within;
        } else if (within) {
          better = bricks < bestBricks || (bricks == bestBricks && texels < bestTexels);
        } else {
          better = texels + bricks * kTexelsPerBrick < bestTexels + bestBricks * kTexelsPerBrick;
        }
        if (better) {
          best[0] = &x, best[1] = &y, best[2] = &z;
          bestWithin = within;
          bestBricks = bricks;
          bestTexels = texels;
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

double BrickLayout::storedTexels() const {
  return storedSide(dims_.x, std::size_t(counts_.x)) * storedSide(dims_.y, std::size_t(counts_.y)) *
         storedSide(dims_.z, std::size_t(counts_.z));
}

std::uint64_t BrickLayout::largestTexels() const {
  std::uint64_t largest = 0;
  for (const Brick& b : bricks_) {
    largest = std::max(largest, std::uint64_t(b.size.x) * b.size.y * b.size.z);
  }
  return largest;
}

}  // namespace vsil
