// The combine rules of core/composition.h against the sequential fold: every sequence of up to
// six samples, split at every point (and at every pair of points, for associativity), must give
// the bytes the unsplit fold gives.
#include "core/composition.h"

#include <cstring>
#include <vector>

#include <gtest/gtest.h>

namespace vsil::composition {
namespace {

constexpr int kMaxLength = 6;

bool sameBits(float a, float b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

// Every sequence of length 0..kMaxLength over `alphabet` symbols.
template <typename F>
void forEachSequence(int alphabet, F&& visit) {
  std::vector<int> seq;
  for (int length = 0; length <= kMaxLength; ++length) {
    seq.assign(std::size_t(length), 0);
    while (true) {
      visit(seq);
      int i = 0;
      while (i < length && ++seq[std::size_t(i)] == alphabet) seq[std::size_t(i++)] = 0;
      if (i == length) break;
    }
  }
}

// Depths of consecutive slices, not representable sums, so that a wrong pairing shows.
float depthOf(std::size_t i) {
  return 0.1f + 0.137f * float(i);
}

void expectSameNk(const NkRun& split, const NkRun& whole, const std::string& what) {
  EXPECT_EQ(split.first.has_value(), whole.first.has_value()) << what;
  if (split.first && whole.first) {
    EXPECT_EQ(*split.first, *whole.first) << what;
  }
  ASSERT_EQ(split.t, whole.t) << what;
  if (whole.t != PixelState::Empty) {
    EXPECT_TRUE(sameBits(split.depth(), whole.depth()))
        << what << ": " << split.depth() << " vs " << whole.depth();
  }
  if (whole.first) {
    EXPECT_TRUE(sameBits(split.last, whole.last)) << what;
  }
}

TEST(Composition, SilhouettePairEqualsTheSequentialFoldAtEverySplit) {
  int checked = 0;
  forEachSequence(3, [&](const std::vector<int>& seq) {
    std::vector<NkSample> samples;
    std::string text;
    for (std::size_t i = 0; i < seq.size(); ++i) {
      samples.push_back({PixelState(seq[i]), depthOf(i)});
      text += "EFC"[seq[i]];
    }
    const NkRun whole = foldNk(samples);
    const std::span<const NkSample> all(samples);
    for (std::size_t a = 0; a <= samples.size(); ++a) {
      const NkRun split = combine(foldNk(all.first(a)), foldNk(all.subspan(a)));
      expectSameNk(split, whole, text + " split at " + std::to_string(a));
      for (std::size_t b = a; b <= samples.size(); ++b) {
        const NkRun x = foldNk(all.first(a)), y = foldNk(all.subspan(a, b - a)),
                    z = foldNk(all.subspan(b));
        expectSameNk(combine(combine(x, y), z), whole, text + " ((x y) z) " + std::to_string(b));
        expectSameNk(combine(x, combine(y, z)), whole, text + " (x (y z)) " + std::to_string(b));
        ++checked;
      }
    }
  });
  EXPECT_GT(checked, 10000);
}

TEST(Composition, SilhouettePairFollowsTheIssuesTable) {
  // A front ending on CONTOUR meets a back starting EMPTY: detected between the runs, halfway
  // between the first hit and the front's last sample.
  const NkSample front[] = {{PixelState::Contour, 0.25f}, {PixelState::Contour, 0.5f}};
  const NkSample back[] = {{PixelState::Empty, 0.75f}};
  const NkRun run = combine(foldNk(front), foldNk(back));
  EXPECT_EQ(run.t, PixelState::Silhouette);
  EXPECT_EQ(run.depth(), 0.5f * (0.25f + 0.5f));
}

TEST(Composition, MaxAndItsFirstDepthEqualTheSequentialFoldAtEverySplit) {
  forEachSequence(4, [&](const std::vector<int>& seq) {
    std::vector<float> values, depths;
    for (std::size_t i = 0; i < seq.size(); ++i) {
      values.push_back(float(seq[i]));
      depths.push_back(depthOf(i));
    }
    const MaxRun whole = foldMax(values, depths);
    const std::span<const float> v(values), d(depths);
    for (std::size_t a = 0; a <= values.size(); ++a) {
      const MaxRun split =
          combine(foldMax(v.first(a), d.first(a)), foldMax(v.subspan(a), d.subspan(a)));
      ASSERT_EQ(split.any, whole.any);
      EXPECT_EQ(split.value, whole.value);
      EXPECT_TRUE(sameBits(split.depth, whole.depth));
    }
  });
}

TEST(Composition, LmipRunEqualsTheSequentialFoldAtEverySplit) {
  for (const float threshold : {0.0f, 1.0f, 2.0f, 3.0f, 4.0f}) {
    forEachSequence(4, [&](const std::vector<int>& seq) {
      std::vector<float> values, depths;
      std::string text;
      for (std::size_t i = 0; i < seq.size(); ++i) {
        values.push_back(float(seq[i]));
        depths.push_back(depthOf(i));
        text += char('0' + seq[i]);
      }
      const LmipRun whole = foldLmip(values, depths, threshold);
      const std::span<const float> v(values), d(depths);
      const auto expectSame = [&](const LmipRun& split, const std::string& what) {
        ASSERT_EQ(split.any, whole.any) << what;
        ASSERT_EQ(split.hasTop, whole.hasTop) << what;
        if (whole.hasTop) {
          EXPECT_EQ(split.top, whole.top) << what;
          EXPECT_TRUE(sameBits(split.topDepth, whole.topDepth)) << what;
          EXPECT_EQ(split.done, whole.done) << what;
        } else {
          EXPECT_EQ(split.max, whole.max) << what;
        }
      };
      for (std::size_t a = 0; a <= values.size(); ++a) {
        const std::string what =
            text + " threshold " + std::to_string(threshold) + " split " + std::to_string(a);
        expectSame(combine(foldLmip(v.first(a), d.first(a), threshold),
                           foldLmip(v.subspan(a), d.subspan(a), threshold)),
                   what);
        for (std::size_t b = a; b <= values.size(); ++b) {
          const LmipRun x = foldLmip(v.first(a), d.first(a), threshold),
                        y = foldLmip(v.subspan(a, b - a), d.subspan(a, b - a), threshold),
                        z = foldLmip(v.subspan(b), d.subspan(b), threshold);
          expectSame(combine(combine(x, y), z), what + " ((x y) z) " + std::to_string(b));
          expectSame(combine(x, combine(y, z)), what + " (x (y z)) " + std::to_string(b));
        }
      }
    });
  }
}

}  // namespace
}  // namespace vsil::composition
