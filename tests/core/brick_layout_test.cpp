// BrickLayout (core/brick_layout.h): which bricks a volume is cut into. Checked against what
// the layout must guarantee, computed here on its own: every sample position of the volume is
// owned by exactly one brick along each axis, each brick stores the voxels its samples and
// their central-difference neighbours read (two of overlap), texture sizes are powers of two
// within the limits, and the texels stay within kMaxWaste of what must be stored.
#include "core/brick_layout.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/limits.h"

namespace vsil {
namespace {

constexpr std::size_t kR16F = 2;  // texel bytes of 8-bit data
constexpr std::size_t kR32F = 4;
constexpr std::uint64_t kLimit = limits::kMaxTextureBytes;
constexpr int kSide = 2048;
// A limit that 512³ R16F texels (256 MiB) fit but whose half a 512³ texture for 257³-300³
// voxels exceeds in padding.
constexpr std::uint64_t kTight = std::uint64_t(300) << 20;  // llvmpipe's GL_MAX_3D_TEXTURE_SIZE

std::string dimsText(glm::ivec3 d) {
  return std::to_string(d.x) + "x" + std::to_string(d.y) + "x" + std::to_string(d.z);
}

// The texture sizes along axis `a` (the bricks of the first row along it).
std::vector<int> sizesAlong(const BrickLayout& layout, int a) {
  std::vector<int> sizes;
  const glm::ivec3 counts = layout.counts();
  for (int i = 0; i < counts[a]; ++i) {
    glm::ivec3 index(0);
    index[a] = i;
    const auto n =
        (std::size_t(index.z) * counts.y + std::size_t(index.y)) * counts.x + std::size_t(index.x);
    sizes.push_back(layout.bricks()[n].size[a]);
  }
  return sizes;
}

// Ownership and storage along every axis, powers of two, the limits; returns false (with
// failures reported) on the first broken brick so that a sweep stops early.
bool expectValid(const BrickLayout& layout, std::uint64_t maxTexels, int maxSide) {
  const glm::ivec3 dims = layout.dims();
  const glm::ivec3 counts = layout.counts();
  const std::string where = dimsText(dims) + " in " + dimsText(counts) + " bricks";
  EXPECT_EQ(layout.size(), std::size_t(counts.x) * counts.y * counts.z) << where;
  EXPECT_LE(layout.largestTexels(), maxTexels) << where;
  for (const Brick& brick : layout.bricks()) {
    for (int a = 0; a < 3; ++a) {
      const int size = brick.size[a];
      if (size < 1 || (size & (size - 1)) != 0 || size > std::max(8, maxSide)) {
        ADD_FAILURE() << where << ": brick " << dimsText(brick.index) << " size " << size;
        return false;
      }
      // Neighbours along the axis share their border; the ends are unbounded.
      const bool first = brick.index[a] == 0, last = brick.index[a] + 1 == counts[a];
      if (first != (brick.low[a] <= -1e29) || last != (brick.high[a] >= 1e29)) {
        ADD_FAILURE() << where << ": brick " << dimsText(brick.index) << " axis " << a << " ends "
                      << brick.low[a] << ", " << brick.high[a];
        return false;
      }
      // The voxels a sample in [low, high] reads (trilinear taps, and those of the central
      // differences one voxel away), within the volume.
      const double low = std::max(brick.low[a], -0.5),
                   high = std::min(brick.high[a], dims[a] - 0.5);
      const int needFirst = std::max(0, int(std::floor(low)) - 1);
      const int needLast = std::min(dims[a] - 1, int(std::floor(high)) + 2);
      if (needFirst < brick.origin[a] || needLast > brick.origin[a] + size - 1) {
        ADD_FAILURE() << where << ": brick " << dimsText(brick.index) << " axis " << a << " owns ["
                      << low << ", " << high << "] and needs voxels " << needFirst << ".."
                      << needLast << " but stores " << brick.origin[a] << ".."
                      << brick.origin[a] + size - 1;
        return false;
      }
    }
  }
  for (int a = 0; a < 3; ++a) {
    for (std::size_t n = 0; n + 1 < layout.size(); ++n) {
      const Brick& b = layout.bricks()[n];
      if (b.index[a] + 1 >= counts[a]) continue;
      glm::ivec3 next = b.index;
      ++next[a];
      const Brick& c =
          layout.bricks()[(std::size_t(next.z) * counts.y + std::size_t(next.y)) * counts.x +
                          std::size_t(next.x)];
      if (b.high[a] != c.low[a]) {
        ADD_FAILURE() << where << ": bricks " << dimsText(b.index) << " and " << dimsText(c.index)
                      << " meet at " << b.high[a] << " and " << c.low[a];
        return false;
      }
    }
  }
  return true;
}

// Within kMaxWaste of the voxels and overlap stored, or one texture whose padding is within
// kPaddingShareOfLimit of `limit`.
bool withinWaste(const BrickLayout& layout, std::size_t texelBytes, std::uint64_t limit) {
  const glm::ivec3 d = layout.dims();
  const std::uint64_t voxels = std::uint64_t(d.x) * d.y * d.z;
  const double ratio = double(layout.texels()) / layout.storedTexels();
  if (ratio <= BrickLayout::kMaxWaste) return true;
  return layout.size() == 1 && double((layout.texels() - voxels) * texelBytes) <=
                                   BrickLayout::kPaddingShareOfLimit * double(limit);
}

TEST(BrickLayout, ThreeHundredCubedIsOneTextureUnlessItsPaddingIsTooLarge) {
  // Under the default limit one texture of 512³ (4.97 times the voxels, 202 MiB of padding
  // in R16F): a frame in one brick is faster than in several.
  const BrickLayout whole = BrickLayout::choose(glm::ivec3(300), kR16F, kLimit, kSide);
  EXPECT_EQ(whole.size(), 1u);
  EXPECT_EQ(whole.texels(), 512ull * 512 * 512);
  // Under a 300 MiB limit that padding is too large (more than half of it): 256 + 64 texels per
  // axis, 320³ (1.21 times the voxels).
  const BrickLayout layout = BrickLayout::choose(glm::ivec3(300), kR16F, kTight, kSide);
  EXPECT_EQ(layout.counts(), glm::ivec3(2));
  for (int a = 0; a < 3; ++a) EXPECT_EQ(sizesAlong(layout, a), (std::vector<int>{256, 64}));
  EXPECT_EQ(layout.texels(), 320ull * 320 * 320);
  EXPECT_TRUE(expectValid(layout, kTight / kR16F, kSide));
  // What cannot follow bricks asks for one texture when it fits.
  const BrickLayout one = BrickLayout::choose(glm::ivec3(300), kR16F, kTight, kSide,
                                              BrickLayout::Bricking::OneIfItFits);
  EXPECT_EQ(one.size(), 1u);
  EXPECT_EQ(one.texels(), 512ull * 512 * 512);
}

TEST(BrickLayout, JustOverAPowerOfTwoAddsASmallBrick) {
  const BrickLayout layout = BrickLayout::choose(glm::ivec3(257), kR16F, kTight, kSide);
  EXPECT_EQ(layout.counts(), glm::ivec3(2));
  for (int a = 0; a < 3; ++a) EXPECT_EQ(sizesAlong(layout, a), (std::vector<int>{256, 8}));
  EXPECT_TRUE(expectValid(layout, kTight / kR16F, kSide));
  // The brick after 256 may be smaller than the rest takes in one: 400 = 256 + 128 + 32, not
  // 256 + 256 (under a limit that 512³ R16F texels exceed).
  const std::uint64_t below512 = std::uint64_t(200) << 20;
  const BrickLayout four = BrickLayout::choose(glm::ivec3(400), kR16F, below512, kSide);
  EXPECT_EQ(sizesAlong(four, 0), (std::vector<int>{256, 128, 32}));
  EXPECT_TRUE(expectValid(four, below512 / kR16F, kSide));
}

TEST(BrickLayout, ThinVolumesTakeTheSmallestBrick) {
  // Axes of fewer than 8 voxels still take 8 texels (a brick holds two of overlap on each side).
  for (glm::ivec3 dims : {glm::ivec3(4, 3, 5), glm::ivec3(1), glm::ivec3(256, 256, 2)}) {
    const BrickLayout layout = BrickLayout::choose(dims, kR16F, kLimit, kSide);
    EXPECT_EQ(layout.size(), 1u) << dimsText(dims);
    EXPECT_TRUE(expectValid(layout, kLimit / kR16F, kSide)) << dimsText(dims);
  }
}

TEST(BrickLayout, PowersOfTwoAndSmallPaddingStayOneBrick) {
  for (glm::ivec3 dims : {glm::ivec3(512), glm::ivec3(256, 256, 128), glm::ivec3(41),
                          glm::ivec3(128, 128, 62), glm::ivec3(256, 256, 130)}) {
    const BrickLayout layout = BrickLayout::choose(dims, kR32F, kLimit, kSide);
    EXPECT_EQ(layout.size(), 1u) << dimsText(dims);
    EXPECT_TRUE(withinWaste(layout, kR32F, kLimit)) << dimsText(dims);
  }
}

TEST(BrickLayout, LargeVolumesTakeFewBricksWithLittleOverlap) {
  struct Case {
    glm::ivec3 dims;
    std::size_t bricks;
  };
  // 1000³ 8-bit: one texture would be 1024³ R16F, 2 GiB (over 1808 MiB): two bricks.
  // 2048²·1024: 8 GiB; slabs of 2048·256·1024 (1 GiB) along y.
  for (const Case& c : {Case{glm::ivec3(1000), 2}, Case{glm::ivec3(1024), 3},
                        Case{glm::ivec3(2048, 2048, 1024), 9}}) {
    const BrickLayout layout = BrickLayout::choose(c.dims, kR16F, kLimit, kSide);
    EXPECT_EQ(layout.size(), c.bricks) << dimsText(c.dims);
    EXPECT_TRUE(expectValid(layout, kLimit / kR16F, kSide));
    EXPECT_LE(double(layout.texels()) / layout.storedTexels(), BrickLayout::kMaxWaste)
        << dimsText(c.dims);
    const double voxels = double(c.dims.x) * c.dims.y * c.dims.z;
    EXPECT_LT(double(layout.texels()) / voxels, 1.08) << dimsText(c.dims);
  }
}

TEST(BrickLayout, SmallTextureLimitsGiveManySmallBricks) {
  // --max-texture-mib 1 at R32F: at most 2^18 texels (64³) per brick.
  const BrickLayout layout = BrickLayout::choose(glm::ivec3(300, 200, 77), kR32F, 1 << 20, kSide);
  EXPECT_GT(layout.size(), 27u);
  EXPECT_TRUE(expectValid(layout, (1 << 20) / kR32F, kSide));
  EXPECT_TRUE(withinWaste(layout, kR32F, 1 << 20));
  EXPECT_THROW(BrickLayout::choose(glm::ivec3(64), kR32F, 1000, kSide), std::invalid_argument);
}

// Every size from 1 to 2100 along one axis, the others a few sizes: valid, and the texels
// within kMaxWaste of the voxels and overlap stored (or one texture within its padding share).
TEST(BrickLayout, WasteIsBoundedOverASweepOfSizes) {
  double worst = 0;
  glm::ivec3 worstDims(0);
  for (int n = 1; n <= 2100; ++n) {
    for (glm::ivec3 dims : {glm::ivec3(n), glm::ivec3(n, 300, 19), glm::ivec3(1000, 777, n)}) {
      const BrickLayout layout = BrickLayout::choose(dims, kR16F, kLimit, kSide);
      ASSERT_TRUE(expectValid(layout, kLimit / kR16F, kSide));
      ASSERT_TRUE(withinWaste(layout, kR16F, kLimit))
          << dimsText(dims) << ": " << layout.texels() << " texels for " << layout.storedTexels()
          << " stored, " << layout.size() << " bricks";
      if (layout.size() > 1) {
        const double ratio = double(layout.texels()) / layout.storedTexels();
        if (ratio > worst) worst = ratio, worstDims = dims;
      }
    }
  }
  RecordProperty("worst_bricked_ratio", std::to_string(worst) + " at " + dimsText(worstDims));
}

// withStorage (the tests' forced layouts): every brick of that size but the last along an
// axis, which is the smallest power of two holding the rest.
TEST(BrickLayout, WithStorageCutsUniformly) {
  const BrickLayout layout = BrickLayout::withStorage(glm::ivec3(100, 20, 8), glm::ivec3(32, 8, 8));
  EXPECT_EQ(sizesAlong(layout, 0), (std::vector<int>{32, 32, 32, 32}));
  EXPECT_EQ(sizesAlong(layout, 1), (std::vector<int>{8, 8, 8, 8, 8}));
  EXPECT_EQ(sizesAlong(layout, 2), (std::vector<int>{8}));
  EXPECT_TRUE(expectValid(layout, 32 * 8 * 8, 32));
  EXPECT_THROW(BrickLayout::withStorage(glm::ivec3(10), glm::ivec3(4)), std::invalid_argument);
}

}  // namespace
}  // namespace vsil
