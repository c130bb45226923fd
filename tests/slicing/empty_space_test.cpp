// Empty-space skipping (slicing/empty_space.h): the brick maxima bound every filtered sample,
// the entry and exit depths are where view rays meet the occupied bricks (checked against a
// CPU ray-box intersection), and turning skipping on changes no pixel of any technique.
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <type_traits>
#include <vector>

#include <gtest/gtest.h>

#include "frame_compare.h"
#include "gl_harness.h"
#include "slice_sampler.h"
#include "slicing/empty_space.h"
#include "slicing/gl_objects.h"
#include "slicing/renderer.h"
#include "slicing/technique.h"
#include "slicing/technique_table.h"

namespace vsil {
namespace {

constexpr int kB = BrickRanges::kBrickSize;

// Sparse: -1 almost everywhere, random peaks at about one voxel in 200, so that each brick's
// maximum comes from a few voxels and a brick that misses one of its reach shows.
Volume randomVolume(glm::ivec3 dims, unsigned seed) {
  Volume volume;
  volume.name = "random";
  volume.dims = dims;
  volume.allocate(SampleType::Float32);
  std::mt19937 random(seed);
  std::uniform_real_distribution<float> value(0.0f, 5.0f), chance(0.0f, 1.0f);
  for (float& v : volume.samples<float>()) v = chance(random) < 0.005f ? value(random) : -1.0f;
  return volume;
}

// Zero everywhere but single voxels of value 1 at `spikes`.
Volume spikesVolume(glm::ivec3 dims, const std::vector<glm::ivec3>& spikes) {
  Volume volume;
  volume.name = "spikes";
  volume.dims = dims;
  volume.allocate(SampleType::Float32);
  for (const auto& s : spikes) volume.samples<float>()[volume.index(s.x, s.y, s.z)] = 1.0f;
  return volume;
}

// The range of the voxels a brick's samples filter (brick * kB - 2 .. (brick + 1) * kB + 1 along
// each axis, within the volume), by brute force.
ValueRange filterReachRange(const Volume& volume, glm::ivec3 brick) {
  const glm::ivec3 lo = glm::max(brick * kB - 2, glm::ivec3(0));
  const glm::ivec3 hi = glm::min((brick + 1) * kB + 1, volume.dims - 1);
  ValueRange range{std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity()};
  for (int z = lo.z; z <= hi.z; ++z) {
    for (int y = lo.y; y <= hi.y; ++y) {
      for (int x = lo.x; x <= hi.x; ++x) {
        range.max = std::max(range.max, volume.at(x, y, z));
        range.min = std::min(range.min, volume.at(x, y, z));
      }
    }
  }
  return range;
}

void expectEachBricksFilterReachRange(const Volume& volume, const std::string& what) {
  const BrickRanges ranges(volume);
  for (int bz = 0; bz < ranges.bricks().z; ++bz) {
    for (int by = 0; by < ranges.bricks().y; ++by) {
      for (int bx = 0; bx < ranges.bricks().x; ++bx) {
        const glm::ivec3 brick(bx, by, bz);
        const ValueRange expected = filterReachRange(volume, brick);
        EXPECT_EQ(ranges.range(brick).max, expected.max)
            << what << " " << bx << "," << by << "," << bz;
        EXPECT_EQ(ranges.range(brick).min, expected.min)
            << what << " " << bx << "," << by << "," << bz;
      }
    }
  }
}

TEST(BrickRanges, EqualTheRangeOverEachBricksFilterReach) {
  // Dims that are not multiples of the brick size: the last bricks are partial.
  const Volume volume = randomVolume({2 * kB + 5, kB + 3, 3 * kB + 1}, 7);
  ASSERT_EQ(BrickRanges(volume).bricks(), glm::ivec3(3, 2, 4));
  expectEachBricksFilterReachRange(volume, "sparse peaks");
}

// Dense noise, so that every brick's minimum and maximum come from voxels of its own, in the
// integer and float types, along rows of every length around the bricks' ends and the halves
// the rows are read in.
TEST(BrickRanges, EqualTheRangeOverEachBricksFilterReachForEveryRowLength) {
  std::mt19937 random(11);
  for (const SampleType type : kSampleTypes) {
    for (int length = 1; length <= 3 * kB + 2; ++length) {
      Volume volume;
      volume.name = "noise";
      volume.dims = {length, 3, kB + 3};
      volume.allocate(type);
      volume.visit([&](auto samples) {
        using T = std::remove_reference_t<decltype(samples[0])>;
        const int offset = std::is_signed_v<T> ? 100 : 0;  // -100 .. 99 where signed
        for (T& v : samples) v = T(int(random() % 200) - offset);
      });
      expectEachBricksFilterReachRange(
          volume, std::string(sampleTypeName(type)) + " row of " + std::to_string(length));
    }
  }
}

TEST(BrickRanges, TheirUnionIsTheVolumesValueRange) {
  for (const glm::ivec3 dims : {glm::ivec3(1, 1, 1), glm::ivec3(2 * kB + 5, kB + 3, 3 * kB + 1),
                                glm::ivec3(kB, 2 * kB, 7)}) {
    for (unsigned seed = 1; seed <= 5; ++seed) {
      Volume volume = randomVolume(dims, seed);
      // One extreme at a random voxel (a corner or an edge of the last, partial bricks too).
      std::mt19937 random(seed);
      volume.samples<float>()[random() % volume.sampleCount()] = seed % 2 ? 9.0f : -7.0f;
      const ValueRange expected = valueRange(volume), whole = BrickRanges(volume).whole();
      EXPECT_EQ(whole.min, expected.min) << seed;
      EXPECT_EQ(whole.max, expected.max) << seed;
    }
  }
}

TEST(BrickRanges, BoundEveryTrilinearSampleInTheirRegion) {
  const Volume volume = randomVolume({2 * kB + 3, 2 * kB, kB + 7}, 11);
  const BrickRanges ranges(volume);
  const View view = makeView(CameraSpec{}, volume.dims, volume.spacing, {64, 64});
  const reference::SliceSampler sampler(volume, view);
  std::mt19937 random(3);
  int checked = 0;
  for (int i = 0; i < 200000; ++i) {
    glm::vec3 p;
    for (int axis = 0; axis < 3; ++axis) {
      std::uniform_real_distribution<float> along(-0.5f, float(volume.dims[axis]) - 0.5f);
      p[axis] = along(random);
    }
    const glm::ivec3 brick = glm::clamp(glm::ivec3(glm::floor((p + 0.5f) / float(kB))),
                                        glm::ivec3(0), ranges.bricks() - 1);
    ASSERT_TRUE(glm::all(glm::greaterThanEqual(glm::dvec3(p), ranges.regionLow(brick))));
    ASSERT_TRUE(glm::all(glm::lessThanEqual(glm::dvec3(p), ranges.regionHigh(brick))));
    // The sample is a convex combination of voxels within the brick's reach, up to float
    // rounding of the weights (reachesIso allows for it): the brick counts as occupied for
    // any iso value the sample reaches, and the sample is not below the brick's minimum.
    const float value = sampler.sample(p);
    ASSERT_TRUE(reachesIso(value)(ranges.range(brick)))
        << p.x << "," << p.y << "," << p.z << ": " << value << " > " << ranges.range(brick).max;
    ASSERT_GE(value, ranges.range(brick).min - 1e-5f * std::abs(ranges.range(brick).min))
        << p.x << "," << p.y << "," << p.z;
    ++checked;
  }
  EXPECT_EQ(checked, 200000);
}

TEST(BricksReading, HoldEverySamplePositionWhoseNearestVoxelIsSet) {
  // One set voxel at a time, on and beside brick borders: every position within half a voxel
  // of it (what GL_NEAREST reads) lies in the region of a brick marked as reading it, and no
  // brick beyond its reach is marked.
  const glm::ivec3 dims(2 * kB + 5, kB + 3, 3 * kB + 1);
  const glm::ivec3 bricks = (dims + kB - 1) / kB;
  std::mt19937 random(5);
  for (const glm::ivec3 voxel :
       {glm::ivec3(0), glm::ivec3(kB - 1, kB, 2 * kB), glm::ivec3(kB, kB - 1, 3 * kB), dims - 1,
        glm::ivec3(2 * kB + 1, 3, kB + 4)}) {
    std::vector<std::uint8_t> voxels(std::size_t(dims.x) * dims.y * dims.z);
    voxels[(std::size_t(voxel.z) * dims.y + voxel.y) * dims.x + voxel.x] = 1;
    const std::vector<bool> reading = bricksReading(voxels, dims);
    ASSERT_EQ(reading.size(), std::size_t(bricks.x) * bricks.y * bricks.z);
    auto marked = [&](glm::ivec3 b) {
      return bool(reading[(std::size_t(b.z) * bricks.y + b.y) * bricks.x + b.x]);
    };
    std::uniform_real_distribution<float> within(-0.5f, 0.5f);
    for (int i = 0; i < 2000; ++i) {
      const glm::vec3 p =
          glm::vec3(voxel) + glm::vec3(within(random), within(random), within(random));
      if (glm::any(glm::lessThan(p, glm::vec3(-0.5f))) ||
          glm::any(glm::greaterThan(p, glm::vec3(dims) - 0.5f)))
        continue;
      const glm::ivec3 brick =
          glm::clamp(glm::ivec3(glm::floor((p + 0.5f) / float(kB))), glm::ivec3(0), bricks - 1);
      ASSERT_TRUE(marked(brick)) << "voxel " << voxel.x << "," << voxel.y << "," << voxel.z;
    }
    int count = 0;
    for (int bz = 0; bz < bricks.z; ++bz) {
      for (int by = 0; by < bricks.y; ++by) {
        for (int bx = 0; bx < bricks.x; ++bx) {
          const glm::ivec3 b(bx, by, bz);
          count += marked(b);
          // Marked bricks lie within two voxels of the set one.
          if (marked(b)) {
            EXPECT_TRUE(glm::all(glm::greaterThanEqual(voxel, b * kB - 2)));
            EXPECT_TRUE(glm::all(glm::lessThanEqual(voxel, (b + 1) * kB + 1)));
          }
        }
      }
    }
    EXPECT_GE(count, 1);
    EXPECT_LE(count, 8);
  }
}

TEST(OccupiedFaces, OneBrickShowsEachOfItsSixFacesOnExactlyOneSide) {
  const Volume volume = spikesVolume({4 * kB, 4 * kB, 4 * kB}, {{kB + 3, 2 * kB + 4, kB + 5}});
  const BrickRanges ranges(volume);
  const View view = makeView(CameraSpec{}, volume.dims, volume.spacing, {64, 64});
  const auto [entry, exit] = occupiedFaces(ranges, reachesIso(0.5f), view);
  // The spike's filter reach lies inside one brick: 6 faces of 2 triangles, none shared.
  EXPECT_EQ(entry.size() + exit.size(), 6u * 6u);
  EXPECT_GE(entry.size(), 6u);
  EXPECT_GE(exit.size(), 6u);
  // Every vertex lies on the brick's region grown by the margin.
  const glm::ivec3 brick(1, 2, 1);
  const glm::dvec3 lo = ranges.regionLow(brick) - kEntryMargin;
  const glm::dvec3 hi = ranges.regionHigh(brick) + kEntryMargin;
  for (const auto& v : entry) {
    for (int axis = 0; axis < 3; ++axis) {
      EXPECT_GE(v[axis], lo[axis] - 1e-6);
      EXPECT_LE(v[axis], hi[axis] + 1e-6);
    }
  }
  // Nothing is occupied above the spike's value.
  EXPECT_TRUE(occupiedFaces(ranges, reachesIso(1.5f), view).entry.empty());
}

TEST(OccupiedFaces, FacesBetweenTwoOccupiedBricksAreLeftOut) {
  // A spike on a brick border reaches into both bricks along x.
  const Volume volume = spikesVolume({4 * kB, 4 * kB, 4 * kB}, {{2 * kB, kB + 3, kB + 3}});
  const BrickRanges ranges(volume);
  ASSERT_TRUE(reachesIso(0.5f)(ranges.range({1, 1, 1})));
  ASSERT_TRUE(reachesIso(0.5f)(ranges.range({2, 1, 1})));
  ASSERT_FALSE(reachesIso(0.5f)(ranges.range({0, 1, 1})));
  ASSERT_FALSE(reachesIso(0.5f)(ranges.range({3, 1, 1})));
  const View view = makeView(CameraSpec{}, volume.dims, volume.spacing, {64, 64});
  const auto [entry, exit] = occupiedFaces(ranges, reachesIso(0.5f), view);
  EXPECT_EQ(entry.size() + exit.size(), 10u * 6u);  // 12 faces, less the 2 they share
}

// The eye distances [near, far] over which the ray of pixel centre `pixel` (top-left origin)
// crosses the box [lo, hi] (voxel coordinates); empty (near > far) when it misses.
std::pair<double, double> rayThroughBox(const View& view, glm::dvec2 pixel, glm::dvec3 lo,
                                        glm::dvec3 hi) {
  const glm::dmat4 voxelFromEye = glm::inverse(view.eyeFromVoxel);
  const glm::dvec2 ndc = view.ndcFromPixel(pixel);
  const glm::dvec3 at0(voxelFromEye * glm::dvec4(view.eyeAtNdc(ndc, 0.0), 1.0));
  const glm::dvec3 at1(voxelFromEye * glm::dvec4(view.eyeAtNdc(ndc, 1.0), 1.0));
  const glm::dvec3 direction = at1 - at0;  // per unit of eye distance
  double tNear = -1e300, tFar = 1e300;
  for (int axis = 0; axis < 3; ++axis) {
    if (std::abs(direction[axis]) < 1e-15) {
      if (at0[axis] < lo[axis] || at0[axis] > hi[axis]) return {1.0, 0.0};
      continue;
    }
    double t0 = (lo[axis] - at0[axis]) / direction[axis];
    double t1 = (hi[axis] - at0[axis]) / direction[axis];
    if (t0 > t1) std::swap(t0, t1);
    tNear = std::max(tNear, t0);
    tFar = std::min(tFar, t1);
  }
  return {tNear, tFar};
}

double windowDepth(const View& view, double eyeDistance) {
  const glm::dvec4 clip = view.clipFromEye * glm::dvec4(0.0, 0.0, -eyeDistance, 1.0);
  return std::clamp(0.5 * clip.z / clip.w + 0.5, 0.0, 1.0);
}

struct DepthCase {
  std::string name;
  CameraSpec camera;
};

void PrintTo(const DepthCase& c, std::ostream* out) {
  *out << c.name;
}

class EntryAndExitDepth : public test::GlTest, public ::testing::WithParamInterface<DepthCase> {};

// The GL entry and exit depths against a CPU intersection of each pixel's ray with the grown
// regions of the occupied bricks. Pixels whose ray passes within kGraze voxels of a box's edge
// may go either way and are not judged.
TEST_P(EntryAndExitDepth, MatchRaysThroughTheOccupiedBricks) {
  constexpr double kGraze = 0.02;
  const glm::ivec3 dims(5 * kB, 4 * kB, 3 * kB + 3);
  const Volume volume = spikesVolume(
      dims, {{kB + 2, kB + 2, kB + 2}, {3 * kB + 4, 2 * kB, kB + 1}, {dims.x - 1, 0, dims.z - 1}});
  const BrickRanges ranges(volume);
  const float iso = 0.5f;
  const glm::ivec2 size(96, 80);
  const View view = makeView(GetParam().camera, dims, volume.spacing, size);

  std::vector<std::pair<glm::dvec3, glm::dvec3>> boxes;
  for (int bz = 0; bz < ranges.bricks().z; ++bz) {
    for (int by = 0; by < ranges.bricks().y; ++by) {
      for (int bx = 0; bx < ranges.bricks().x; ++bx) {
        if (!reachesIso(iso)(ranges.range({bx, by, bz}))) continue;
        boxes.emplace_back(ranges.regionLow({bx, by, bz}) - kEntryMargin,
                           ranges.regionHigh({bx, by, bz}) + kEntryMargin);
      }
    }
  }
  ASSERT_GE(boxes.size(), 3u);

  gl::RenderTarget target(size, GL_R8UI, /*withDepthStencil=*/true);
  EmptySpaceSkipping skipping;
  glViewport(0, 0, size.x, size.y);
  skipping.prepare(ranges, reachesIso(iso), view, /*enabled=*/true);
  target.bindForDrawing();
  skipping.writeEntryDepth(glm::mat4(view.clipFromVoxel()));
  std::vector<float> entry(std::size_t(size.x * size.y)), exit(entry.size());
  std::vector<float> entryImage(entry.size());
  glReadPixels(0, 0, size.x, size.y, GL_DEPTH_COMPONENT, GL_FLOAT, entry.data());
  skipping.drawEntryDepthImage(glm::mat4(view.clipFromVoxel()));
  glBindTexture(GL_TEXTURE_2D, skipping.exitDepthTexture());
  glGetTexImage(GL_TEXTURE_2D, 0, GL_RED, GL_FLOAT, exit.data());
  glBindTexture(GL_TEXTURE_2D, skipping.entryDepthTexture());
  glGetTexImage(GL_TEXTURE_2D, 0, GL_RED, GL_FLOAT, entryImage.data());
  glBindTexture(GL_TEXTURE_2D, 0);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);

  int judged = 0, hits = 0, misses = 0;
  for (int y = 0; y < size.y; ++y) {
    for (int x = 0; x < size.x; ++x) {
      const glm::dvec2 pixel(x + 0.5, y + 0.5);
      double nearShrunk = 1e300, nearGrown = 1e300, farShrunk = -1e300, farGrown = -1e300;
      for (const auto& [lo, hi] : boxes) {
        const auto grown = rayThroughBox(view, pixel, lo - kGraze, hi + kGraze);
        const auto shrunk = rayThroughBox(view, pixel, lo + kGraze, hi - kGraze);
        if (grown.first <= grown.second) {
          nearGrown = std::min(nearGrown, grown.first);
          farGrown = std::max(farGrown, grown.second);
        }
        if (shrunk.first <= shrunk.second) {
          nearShrunk = std::min(nearShrunk, shrunk.first);
          farShrunk = std::max(farShrunk, shrunk.second);
        }
      }
      const bool surelyHit = nearShrunk < 1e300, surelyMiss = !(nearGrown < 1e300);
      if (!surelyHit && !surelyMiss) continue;
      ++judged;
      const std::size_t i = std::size_t((size.y - 1 - y) * size.x + x);  // GL rows bottom-up
      SCOPED_TRACE("pixel " + std::to_string(x) + "," + std::to_string(y));
      if (surelyMiss) {
        ++misses;
        EXPECT_EQ(entry[i], 1.0f);
        EXPECT_EQ(entryImage[i], 1.0f);
        EXPECT_EQ(exit[i], 0.0f);
        continue;
      }
      ++hits;
      // Where the nearest grazing box decides, the depth lies between the two estimates; the
      // entry image (for the tile march) holds the depth buffer's depth, unquantized.
      constexpr double kDepthTolerance = 1e-5;
      for (const float entryDepth : {entry[i], entryImage[i]}) {
        EXPECT_GE(entryDepth, windowDepth(view, nearGrown) - kDepthTolerance);
        EXPECT_LE(entryDepth, windowDepth(view, nearShrunk) + kDepthTolerance);
      }
      EXPECT_GE(exit[i], windowDepth(view, farShrunk) - kDepthTolerance);
      EXPECT_LE(exit[i], windowDepth(view, farGrown) + kDepthTolerance);
    }
  }
  EXPECT_GT(hits, 50);
  EXPECT_GT(misses, size.x * size.y / 8);  // many rays miss three small bricks
  EXPECT_GT(judged, size.x * size.y * 9 / 10);
}

CameraSpec camera(double azimuth, double elevation, bool orthographic, double zoom) {
  CameraSpec spec;
  spec.azimuthDeg = azimuth;
  spec.elevationDeg = elevation;
  spec.orthographic = orthographic;
  spec.zoom = zoom;
  return spec;
}

INSTANTIATE_TEST_SUITE_P(Views, EntryAndExitDepth,
                         ::testing::Values(DepthCase{"Default", camera(30, 20, false, 1)},
                                           DepthCase{"AxisAligned", camera(0, 0, false, 1)},
                                           DepthCase{"Orthographic", camera(-65, 40, true, 1.3)},
                                           DepthCase{"ZoomedIn", camera(150, -30, false, 3)}),
                         [](const auto& info) { return info.param.name; });

struct SceneCase {
  std::string name;
  std::string technique;
  OptionValues options;
  CameraSpec camera;
};

void PrintTo(const SceneCase& c, std::ostream* out) {
  *out << c.name;
}

class SkippingChangesNoPixel : public test::GlTest,
                               public ::testing::WithParamInterface<SceneCase> {};

// Spikes whose filter reach crosses brick borders, edges and corners, and the volume's own
// faces: the worst case for a conservative bound. Skipping on and off must agree exactly.
TEST_P(SkippingChangesNoPixel, OnSpikesAtBrickBorders) {
  const SceneCase& c = GetParam();
  const glm::ivec3 dims(3 * kB + 2, 3 * kB, 2 * kB + 5);
  const Volume volume = spikesVolume(dims, {{kB - 1, kB - 1, kB - 1},
                                            {kB, 2 * kB, kB + 3},
                                            {2 * kB - 1, kB + 4, 2 * kB},
                                            {0, 0, 0},
                                            {dims.x - 1, dims.y - 1, dims.z - 1},
                                            {dims.x - 1, kB / 2, 0}});
  Renderer renderer(test::sharedGlContext());
  renderer.setVolume(volume);
  RenderSettings settings;
  settings.technique = c.technique;
  settings.options = c.options;
  settings.size = {120, 100};
  settings.camera = c.camera;
  settings.emptySpaceSkipping = false;
  const RenderResult all = renderer.render(settings);
  settings.emptySpaceSkipping = true;
  const RenderResult skipped = renderer.render(settings);

  EXPECT_EQ(test::differingPixels(all.frame, skipped.frame), 0);
  // The defaults from the histogram (Otsu's threshold: the MIP family's window, illustrate's
  // opacity, the default rule base) leave the spikes' cores: 19 pixels in the orthographic view,
  // 8 in semantic's zoomed-in one (its samples start half a step into the box).
  EXPECT_GT(test::shownPixels(all.frame), 5)
      << "the spikes must show, or the comparison says nothing";
}

std::vector<SceneCase> sceneCases() {
  const std::vector<std::pair<std::string, CameraSpec>> views = {
      {"Default", camera(30, 20, false, 1)},
      {"Behind", camera(200, -35, false, 1.5)},
      {"Orthographic", camera(95, 60, true, 1)},
      {"ZoomedIn", camera(-20, 10, false, 2.5)}};
  // Every technique of the table (each decides for itself what is occupied), with each of its
  // pipelines (each skips its own way).
  std::vector<SceneCase> cases;
  for (const auto& [viewName, spec] : views) {
    for (const auto& technique : techniqueTable()) {
      const OptionSpec* pipeline = technique.option("pipeline");
      for (const std::string& choice :
           pipeline ? pipeline->choices : std::vector<std::string>{""}) {
        OptionValues options = test::isoOptions(technique, 0.2);
        if (!choice.empty()) options["pipeline"] = choice;
        cases.push_back({technique.name + viewName + (choice.empty() ? "" : "_" + choice),
                         technique.name, options, spec});
      }
    }
    // Halos add opacity beside the spikes, in bricks their values leave empty
    // (Technique::alsoOccupied).
    OptionValues halo;
    halo["effects"] = std::string("halo");
    halo["param"] = std::vector<std::string>{"k_os=4,k_hr=5,k_ho=3"};
    cases.push_back({"illustrate_halo" + viewName, "illustrate", halo, spec});
  }
  return cases;
}

INSTANTIATE_TEST_SUITE_P(Scenes, SkippingChangesNoPixel, ::testing::ValuesIn(sceneCases()),
                         [](const auto& info) { return info.param.name; });

}  // namespace
}  // namespace vsil
