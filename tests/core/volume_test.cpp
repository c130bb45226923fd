// Volume keeps its samples in their own type: the accessors every consumer uses (visit,
// samples<T>, value, at, valueRange) agree with what was written, per type; the checks that
// run before a reader allocates (planVolume, resolveRegion) and the render's memory model.
#include "core/volume.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "core/error.h"

namespace vsil {
namespace {

// Fills a 5x4x3 volume of `type` with value(i) = a type-specific pattern, through the typed
// view, and returns the volume.
template <typename C>
Volume patterned(glm::ivec3 dims, C (*pattern)(std::size_t)) {
  Volume volume;
  volume.dims = dims;
  volume.allocate(sampleTypeFor<C>());
  const std::span<C> samples = volume.samples<C>();
  for (std::size_t i = 0; i < samples.size(); ++i) samples[i] = pattern(i);
  return volume;
}

template <typename C>
void expectAccessorsAgree(C (*pattern)(std::size_t), SampleType type, std::size_t bytes) {
  SCOPED_TRACE(sampleTypeName(type));
  const glm::ivec3 dims(5, 4, 3);
  const Volume volume = patterned<C>(dims, pattern);
  EXPECT_EQ(volume.type(), type);
  EXPECT_EQ(sampleTypeSize(type), bytes);
  EXPECT_EQ(volume.sampleCount(), 60u);
  EXPECT_EQ(volume.sampleBytes(), 60u * bytes);
  float lo = std::numeric_limits<float>::infinity(), hi = -lo;
  for (int z = 0; z < dims.z; ++z) {
    for (int y = 0; y < dims.y; ++y) {
      for (int x = 0; x < dims.x; ++x) {
        const std::size_t i = volume.index(x, y, z);
        EXPECT_EQ(i, std::size_t(x + 5 * (y + 4 * z)));
        const float expected = float(pattern(i));
        EXPECT_EQ(volume.at(x, y, z), expected) << x << "," << y << "," << z;
        EXPECT_EQ(volume.value(i), expected);
        lo = std::min(lo, expected);
        hi = std::max(hi, expected);
      }
    }
  }
  const ValueRange range = valueRange(volume);
  EXPECT_EQ(range.min, lo);
  EXPECT_EQ(range.max, hi);
  // visit hands out the samples in their own type, the same memory as samples<C>().
  const bool sameSpan = volume.visit([&](auto samples) {
    if constexpr (std::is_same_v<typename decltype(samples)::value_type, C>) {
      return samples.data() == volume.samples<C>().data() && samples.size() == 60;
    }
    return false;
  });
  EXPECT_TRUE(sameSpan);
}

TEST(Volume, AccessorsAgreeForEveryType) {
  expectAccessorsAgree<std::uint8_t>([](std::size_t i) { return std::uint8_t(255 - i * 4); },
                                     SampleType::UInt8, 1);
  expectAccessorsAgree<std::int8_t>([](std::size_t i) { return std::int8_t(int(i) * 4 - 128); },
                                    SampleType::Int8, 1);
  expectAccessorsAgree<std::uint16_t>([](std::size_t i) { return std::uint16_t(65535 - i * 1000); },
                                      SampleType::UInt16, 2);
  expectAccessorsAgree<std::int16_t>(
      [](std::size_t i) { return std::int16_t(int(i) * 1000 - 32768); }, SampleType::Int16, 2);
  expectAccessorsAgree<float>([](std::size_t i) { return float(i) * -0.37f + 1e6f; },
                              SampleType::Float32, 4);
}

TEST(Volume, TypedViewOfAnotherTypeIsALogicError) {
  Volume volume;
  volume.dims = {2, 2, 2};
  volume.allocate(SampleType::UInt16);
  EXPECT_THROW(volume.samples<float>(), std::logic_error);
  EXPECT_THROW(volume.samples<std::int16_t>(), std::logic_error);
  EXPECT_NO_THROW(volume.samples<std::uint16_t>());
}

TEST(Volume, AllocateZeroesAndReplacesTheType) {
  Volume volume;
  volume.dims = {3, 1, 1};
  volume.allocate(SampleType::Float32);
  volume.samples<float>()[1] = 5.0f;
  volume.allocate(SampleType::Int8);
  EXPECT_EQ(volume.type(), SampleType::Int8);
  EXPECT_EQ(volume.sampleBytes(), 3u);
  for (int x = 0; x < 3; ++x) EXPECT_EQ(volume.at(x, 0, 0), 0.0f);
}

TEST(Volume, BorrowedSamplesAreSharedOwnedOnesCopied) {
  std::vector<std::uint16_t> memory{1, 2, 3, 4, 5, 6};
  auto released = std::make_shared<bool>(false);
  Volume borrowed;
  borrowed.dims = {3, 2, 1};
  borrowed.borrow(memory.data(),
                  std::shared_ptr<void>(nullptr, [released](void*) { *released = true; }));
  EXPECT_TRUE(borrowed.borrowsSamples());
  EXPECT_EQ(borrowed.type(), SampleType::UInt16);
  EXPECT_EQ(borrowed.samples<std::uint16_t>().data(), memory.data());
  EXPECT_EQ(borrowed.at(2, 1, 0), 6.0f);
  {
    const Volume copy = borrowed;  // shares, as a numpy view does
    EXPECT_EQ(copy.samples<std::uint16_t>().data(), memory.data());
    borrowed = Volume();
    EXPECT_FALSE(*released);  // the copy still holds the owner
  }
  EXPECT_TRUE(*released);

  auto owner = std::make_shared<Volume>();
  owner->name = "owner";
  owner->dims = {2, 2, 2};
  owner->spacing = {1, 2, 3};
  owner->allocate(SampleType::Float32);
  owner->samples<float>()[7] = 0.5f;
  const Volume deep = *owner;  // owned samples are copied
  EXPECT_NE(deep.samples<float>().data(), owner->samples<float>().data());
  const Volume view = Volume::sharing(owner);
  EXPECT_EQ(view.name, "owner");
  EXPECT_EQ(view.spacing, owner->spacing);
  EXPECT_EQ(view.samples<float>().data(), owner->samples<float>().data());
  EXPECT_EQ(owner->at(1, 1, 1), 0.5f);  // the owner keeps its samples
  EXPECT_FALSE(owner->borrowsSamples());
}

// Samples placed in memory the volume holds (allocateIn: the DICOM child's memfd mapping) are
// its own: not borrowed, released with the last volume moved from it, copied by a copy.
TEST(Volume, HeldSamplesAreTheVolumesOwn) {
  std::vector<std::int16_t> memory{1, 2, 3, 4, 5, 6, 7, 8};
  auto released = std::make_shared<bool>(false);
  Volume held;
  held.dims = {2, 2, 2};
  held.allocateIn(SampleType::Int16,
                  std::shared_ptr<void>(memory.data(), [released](void*) { *released = true; }));
  EXPECT_FALSE(held.borrowsSamples());
  EXPECT_EQ(held.type(), SampleType::Int16);
  EXPECT_EQ(held.samples<std::int16_t>().data(), memory.data());
  EXPECT_EQ(held.at(1, 1, 1), 8.0f);
  Volume copy = held;
  EXPECT_NE(copy.samples<std::int16_t>().data(), memory.data());
  EXPECT_FALSE(copy.borrowsSamples());
  copy.samples<std::int16_t>()[0] = -1;
  EXPECT_EQ(memory[0], 1);  // the copy's samples are its own
  EXPECT_EQ(copy.at(1, 1, 1), 8.0f);
  Volume assigned;
  assigned = held;
  EXPECT_NE(assigned.samples<std::int16_t>().data(), memory.data());
  Volume moved = std::move(held);
  EXPECT_EQ(moved.samples<std::int16_t>().data(), memory.data());
  EXPECT_FALSE(*released);
  moved = Volume();
  EXPECT_TRUE(*released);
  EXPECT_EQ(copy.at(1, 1, 1), 8.0f);
}

// A volume of 1 MiB or more takes its samples from one mapping (Volume::allocate): zero, its
// own, and copied by a copy, like a vector's.
TEST(Volume, ALargeVolumeIsAllocatedZeroAndOwned) {
  Volume large;
  large.dims = {128, 128, 64};
  large.allocate(SampleType::UInt16);  // 2 MiB
  const auto samples = large.samples<std::uint16_t>();
  ASSERT_EQ(samples.size(), large.voxelCount());
  EXPECT_TRUE(std::all_of(samples.begin(), samples.end(), [](auto v) { return v == 0; }));
  EXPECT_FALSE(large.borrowsSamples());
  large.samples<std::uint16_t>().back() = 7;
  Volume copy = large;
  EXPECT_NE(copy.samples<std::uint16_t>().data(), samples.data());
  copy.samples<std::uint16_t>().back() = 9;
  EXPECT_EQ(large.samples<std::uint16_t>().back(), 7);
  large.allocate(SampleType::Float32);  // replaced, type and all
  EXPECT_EQ(large.type(), SampleType::Float32);
  EXPECT_EQ(large.at(127, 127, 63), 0.0f);
}

// Otsu's threshold written out: the level t maximizing the between-class variance of the
// histogram (classes <= t and > t), the first t on ties, as OpenCV takes it.
int bruteForceOtsu(const std::vector<double>& histogram) {
  double total = 0, sum = 0;
  for (std::size_t i = 0; i < histogram.size(); ++i) total += histogram[i], sum += i * histogram[i];
  double best = -1, w0 = 0, sum0 = 0;
  int bestLevel = 0;
  for (std::size_t t = 0; t + 1 < histogram.size(); ++t) {
    w0 += histogram[t];
    sum0 += t * histogram[t];
    const double w1 = total - w0;
    if (w0 == 0 || w1 == 0) continue;
    const double m0 = sum0 / w0, m1 = (sum - sum0) / w1;
    const double between = w0 * w1 * (m0 - m1) * (m0 - m1);
    if (between > best * (1 + 1e-12)) best = between, bestLevel = int(t);
  }
  return bestLevel;
}

TEST(DefaultIso, ABinaryMaskGetsTheMiddleOfItsGap) {
  Volume mask;
  mask.dims = {8, 8, 8};
  mask.allocate(SampleType::UInt8);
  for (std::size_t i = 0; i < mask.sampleCount(); i += 3) mask.samples<std::uint8_t>()[i] = 1;
  EXPECT_EQ(defaultIso(mask), 0.5f);
  // Two values far apart, any proportion: the middle of the empty levels between them.
  for (std::size_t i = 0; i < mask.sampleCount(); ++i) {
    mask.samples<std::uint8_t>()[i] = i % 7 == 0 ? 200 : 10;
  }
  EXPECT_FLOAT_EQ(defaultIso(mask), 10.0f + 128.0f * 190.0f / 256.0f);
}

TEST(DefaultIso, IsOtsusThresholdOfTwoOverlappingClasses) {
  // 16-bit "CT": 70 % soft tissue around 1000, 30 % bone around 3000, and a few outliers.
  Volume ct;
  ct.dims = {64, 64, 32};
  ct.allocate(SampleType::UInt16);
  std::mt19937 random(3);
  std::normal_distribution<double> soft(1000, 150), bone(3000, 400);
  const auto samples = ct.samples<std::uint16_t>();
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const double v = i % 10 < 7 ? soft(random) : bone(random);
    samples[i] = std::uint16_t(std::clamp(v, 0.0, 65535.0));
  }
  const ValueRange range = valueRange(ct);
  const double span = double(range.max) - range.min;
  std::vector<double> histogram(256, 0.0);
  for (const std::uint16_t v : samples) {
    ++histogram[std::min(255, int(std::floor((v - range.min) * 256 / span)))];
  }
  const int t = bruteForceOtsu(histogram);
  const float iso = defaultIso(ct);
  // Overlapping classes leave no gap: the iso is the top of Otsu's level t.
  EXPECT_NEAR(iso, range.min + (t + 1) * span / 256, 1e-3 * span);
  EXPECT_GT(iso, 1500.0f);  // between the classes, not the range's middle alone
  EXPECT_LT(iso, 2500.0f);
  // A constant volume: its value.
  Volume flat;
  flat.dims = {2, 2, 2};
  flat.allocate(SampleType::Float32);
  for (float& v : flat.samples<float>()) v = 3.5f;
  EXPECT_EQ(defaultIso(flat), 3.5f);
}

// otsuLevel against cv::threshold's THRESH_OTSU on an image holding the histogram's levels
// (what the default iso came from before): the same level for histograms of every shape, ties
// and empty levels included.
TEST(DefaultIso, OtsuLevelIsOpenCvsOtsuThreshold) {
  std::mt19937 random(11);
  for (int trial = 0; trial < 400; ++trial) {
    LevelCounts counts{};
    const int shape = trial % 4;
    const int spikes = 1 + trial % 5;
    for (int level = 0; level < 256; ++level) {
      if (shape == 0) counts[level] = random() % 50;                            // noise
      if (shape == 1) counts[level] = random() % 8 == 0 ? random() % 1000 : 0;  // sparse
      if (shape == 2) counts[level] = 100 + (level % 32 < 16 ? 0 : 7);          // ties
    }
    for (int k = 0; shape == 3 && k < spikes; ++k) counts[random() % 256] += 1 + random() % 5000;
    std::uint64_t total = 0;
    for (std::uint64_t c : counts) total += c;
    if (total == 0) continue;
    cv::Mat1b image(1, int(total));
    int at = 0;
    for (int level = 0; level < 256; ++level) {
      for (std::uint64_t k = 0; k < counts[level]; ++k) image(0, at++) = std::uint8_t(level);
    }
    cv::Mat1b binary;
    const int opencv =
        int(cv::threshold(image, binary, 0, 255, cv::THRESH_BINARY | cv::THRESH_OTSU));
    EXPECT_EQ(otsuLevel(counts, total), opencv) << "trial " << trial << ", shape " << shape;
  }
}

// The levels of 8- and 16-bit samples come from a table, those of float samples from the
// formula: a volume and its float32 copy get the same defaults (same value range).
TEST(DefaultIso, IntegerSamplesGetTheLevelsOfTheirFloatValues) {
  std::mt19937 random(5);
  const auto check = [&](SampleType type, auto sample) {
    using C = decltype(sample);
    Volume typed;
    typed.dims = {40, 30, 20};
    typed.allocate(type);
    Volume floats;
    floats.dims = typed.dims;
    floats.allocate(SampleType::Float32);
    std::normal_distribution<double> low(0.3, 0.08), high(0.75, 0.1);
    const double lo = double(std::numeric_limits<C>::min()),
                 hi = double(std::numeric_limits<C>::max());
    for (std::size_t i = 0; i < typed.sampleCount(); ++i) {
      const double unit = std::clamp(i % 3 ? low(random) : high(random), 0.0, 1.0);
      const C value = C(std::lround(lo + unit * (hi - lo)));
      typed.samples<C>()[i] = value;
      floats.samples<float>()[i] = float(value);
    }
    const DerivedDefaults a = derivedDefaults(typed), b = derivedDefaults(floats);
    EXPECT_EQ(a.iso, b.iso) << sampleTypeName(type);
    EXPECT_EQ(a.windowHigh, b.windowHigh) << sampleTypeName(type);
    EXPECT_EQ(levelCounts(typed, valueRange(typed), 0, 20),
              levelCounts(floats, valueRange(floats), 0, 20))
        << sampleTypeName(type);
  };
  check(SampleType::UInt8, std::uint8_t());
  check(SampleType::Int8, std::int8_t());
  check(SampleType::UInt16, std::uint16_t());
  check(SampleType::Int16, std::int16_t());
}

TEST(Volume, TypeNamesAndSizes) {
  const char* names[] = {"uint8", "int8", "uint16", "int16", "float32"};
  int i = 0;
  for (SampleType type : kSampleTypes) {
    EXPECT_STREQ(sampleTypeName(type), names[i++]);
    EXPECT_EQ(isIntegerType(type), type != SampleType::Float32);
  }
}

ReadRegion cropOf(std::optional<int> x0, std::optional<int> x1, std::optional<int> y0,
                  std::optional<int> y1, std::optional<int> z0, std::optional<int> z1,
                  int stride = 1) {
  ReadRegion region;
  region.crop = std::array<ReadRegion::Range, 3>{{{x0, x1}, {y0, y1}, {z0, z1}}};
  region.cropText = "test";
  region.stride = stride;
  return region;
}

TEST(VolumeRegion, HalfOpenRangesWithOpenEndsAndStride) {
  // x 2..9 every 3rd: 2, 5, 8 -> 3; y from 1 to the edge (7) every 3rd: 1, 4 -> 2; z all 5: 0, 3
  const ReadRegion region = cropOf(2, 10, 1, std::nullopt, std::nullopt, std::nullopt, 3);
  const VolumeSubset subset = resolveRegion("f", {12, 7, 5}, region);
  EXPECT_EQ(subset.lo, glm::ivec3(2, 1, 0));
  EXPECT_EQ(subset.hi, glm::ivec3(10, 7, 5));
  EXPECT_EQ(subset.dims(), glm::ivec3(3, 2, 2));
  EXPECT_FALSE(subset.whole());
  EXPECT_TRUE(subset.keeps(0, 8));
  EXPECT_FALSE(subset.keeps(0, 9));
  EXPECT_FALSE(subset.keeps(0, 11));
  EXPECT_EQ(subset.keptIndex(0, 8), 2);
  EXPECT_EQ(subset.cropText(), "2:10,1:7,0:5");
  EXPECT_TRUE(resolveRegion("f", {4, 4, 4}, ReadRegion{}).whole());
}

TEST(VolumeRegion, RangesBeyondTheVolumeNameFlagAndFile) {
  const std::string message = [] {
    try {
      resolveRegion("data.raw", {10, 10, 1}, cropOf(0, 11, {}, {}, {}, {}));
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  }();
  EXPECT_EQ(message,
            "data.raw: --crop 'test' ends at x = 11, beyond the volume's 10 samples along x");
  EXPECT_THROW(resolveRegion("f", {10, 10, 1}, cropOf({}, {}, {}, {}, 1, {})), InputError);
}

TEST(PlanVolume, ChecksTheKeptVolumeAgainstTheLimits) {
  VolumeLimits limits;
  limits.maxBytes = std::size_t(1) << 20;
  // 128³ uint8 = 2 MiB: over 1 MiB whole, 256 KiB with stride 2.
  EXPECT_THROW(planVolume("f", glm::ivec3(128), SampleType::UInt8, limits), InputError);
  ReadRegion stride2;
  stride2.stride = 2;
  EXPECT_EQ(planVolume("f", glm::ivec3(128), SampleType::UInt8, limits, stride2).dims(),
            glm::ivec3(64));
  // The same as float32 (4 bytes) still fits; as the task counts it (a render), it does not.
  EXPECT_NO_THROW(planVolume("f", glm::ivec3(64), SampleType::Float32, limits));
  limits.taskBytes = [](glm::ivec3 dims, SampleType type) {
    return limits::renderVolumeBytes(dims, sampleTypeSize(type));
  };
  EXPECT_THROW(planVolume("f", glm::ivec3(64), SampleType::Float32, limits), InputError);
  // Per axis: a file larger than the texture limit is fine when what is kept fits.
  limits = {};
  EXPECT_THROW(planVolume("f", {4096, 8, 8}, SampleType::UInt8, limits), InputError);
  EXPECT_EQ(
      planVolume("f", {4096, 8, 8}, SampleType::UInt8, limits, cropOf(1000, 3000, {}, {}, {}, {}))
          .dims(),
      glm::ivec3(2000, 8, 8));
  EXPECT_THROW(
      planVolume("f", {4096, 8, 8}, SampleType::UInt8, limits, cropOf(0, 4096, {}, {}, {}, {})),
      InputError);
}

TEST(PlanVolume, MemoryMessageNamesSizeLimitAndOptions) {
  VolumeLimits limits;
  limits.maxBytes = std::size_t(100) << 20;
  limits.task = "rendering";
  limits.taskDetail = " at --size 64x64";
  limits.taskBytes = [](glm::ivec3, SampleType) { return std::uint64_t(150) << 20; };
  try {
    planVolume("big.nrrd", {512, 512, 300}, SampleType::UInt16, limits);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              "big.nrrd: rendering 512x512x300 uint16 samples at --size 64x64 needs 150 MiB, over "
              "the --max-memory limit of 100 MiB; read less with --crop X0:X1,Y0:Y1,Z0:Z1 or "
              "--stride N, or raise --max-memory");
  }
}

TEST(Limits, RenderVolumeBytesCountSamplesTextureRangesAndSlabs) {
  const glm::ivec3 dims(512, 512, 512);
  const std::uint64_t voxels = 512ull * 512 * 512;
  // A min and max float per 8³ brick, and two z planes of them per worker thread while built.
  const std::uint64_t ranges =
      8 * (64ull * 64 * 64 + limits::kMaxWorkerThreads * (64ull * 512 + 64ull * 64));
  const std::uint64_t slabs = 2 * limits::kUploadSlabBytes;  // 512² floats = 1 MiB < 8 MiB
  // 8-bit: 1 byte + R16F; wider types: their bytes + R32F (the check precedes the values).
  EXPECT_EQ(limits::renderVolumeBytes(dims, 1), voxels * 3 + ranges + slabs);
  EXPECT_EQ(limits::renderVolumeBytes(dims, 2), voxels * 6 + ranges + slabs);
  EXPECT_EQ(limits::renderVolumeBytes(dims, 4), voxels * 8 + ranges + slabs);
  // Gradient shading: the RGBA16F gradient texture and the gradients on the CPU it is built
  // from.
  EXPECT_EQ(limits::renderVolumeBytes(dims, 1, /*gradients=*/true),
            voxels * (3 + limits::kGradientBytesPerTexel + limits::kGradientCpuBytesPerVoxel) +
                ranges + slabs);
  // A texture is a power of two along each axis (core/brick_layout.h): 300³ in one texture of
  // 512³ (4.97 times the voxels) under the default limit; under a 300 MiB limit, whose half
  // that padding exceeds, in bricks of 256 + 64 texels along each axis (320³) — unless the
  // render needs one texture (the tiles march, illustrate's halos).
  const glm::ivec3 odd(300);
  const std::uint64_t oddVoxels = 300ull * 300 * 300;
  const std::uint64_t oddRanges =
      8 * (38ull * 38 * 38 + limits::kMaxWorkerThreads * (38ull * 300 + 38ull * 38));
  const std::uint64_t tight = std::uint64_t(300) << 20;
  EXPECT_EQ(limits::renderVolumeBytes(odd, 1),
            oddVoxels + 512ull * 512 * 512 * 2 + oddRanges + 2 * limits::kUploadSlabBytes);
  EXPECT_EQ(limits::renderVolumeBytes(odd, 1, false, tight),
            oddVoxels + 320ull * 320 * 320 * 2 + oddRanges + 2 * limits::kUploadSlabBytes);
  EXPECT_EQ(limits::renderVolumeBytes(odd, 1, false, tight, /*oneTexture=*/true),
            oddVoxels + 512ull * 512 * 512 * 2 + oddRanges + 2 * limits::kUploadSlabBytes);
  // 1024³ of 8-bit data takes bricks (one texture would be 2 GiB): a few percent of overlap.
  const std::uint64_t big = 1024ull * 1024 * 1024;
  EXPECT_LT(double(limits::renderVolumeBytes(glm::ivec3(1024), 1)) / double(big), 3.25);
  // About 3.2 bytes per voxel for 8-bit data (3.6 with ranges built for the whole volume at
  // once), against 8 when every volume was floats.
  EXPECT_LT(double(limits::renderVolumeBytes(dims, 1)) / double(voxels), 3.2);
}

}  // namespace
}  // namespace vsil
