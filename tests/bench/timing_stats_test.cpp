// The bench's ratio of two cases from paired frames (harness/timing_stats.h pairedRatio).
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "harness/timing_stats.h"

namespace vsil::bench {
namespace {

// The machine slows down over the run and case a costs 1.2× case b in every turn: 1.2 exactly.
// The same times in other turns give other quotients.
TEST(PairedRatio, TakesTheQuotientTurnByTurn) {
  EXPECT_DOUBLE_EQ(pairedRatio({12, 24, 36, 48, 60}, {10, 20, 30, 40, 50}), 1.2);
  EXPECT_DOUBLE_EQ(pairedRatio({24, 12}, {10, 20}), 1.5);  // the median of 2.4 and 0.6
}

// The median of the quotients: one disturbed turn does not move it.
TEST(PairedRatio, IsTheMedianOfTheTurnsQuotients) {
  EXPECT_DOUBLE_EQ(pairedRatio({11, 30, 13}, {10, 10, 10}), 1.3);
  EXPECT_DOUBLE_EQ(pairedRatio({10, 12, 14, 100}, {10, 10, 10, 10}), 1.3);  // even: the mean
}

TEST(PairedRatio, NoRatioWithoutPairsOrWithATimeNotPositive) {
  EXPECT_TRUE(std::isnan(pairedRatio({}, {})));
  EXPECT_TRUE(std::isnan(pairedRatio({1, 2}, {1})));
  EXPECT_TRUE(std::isnan(pairedRatio({1, 2}, {1, 0})));
  EXPECT_TRUE(std::isnan(pairedRatio({-1, 2}, {1, 1})));
  EXPECT_TRUE(std::isnan(pairedRatio({NAN, 2}, {1, 1})));
}

// A table says when its frame times were unsteady (round 14: a loaded machine's frames swung 2×
// and the table showed 168 fps against 98 with nothing to tell): the worst case named, with
// its fastest and slowest frame; nothing when every case kept within kUnsteadySpread (2).
TEST(UnsteadyNote, NamesTheWorstCaseWhenFramesSpreadPastTheLimit) {
  EXPECT_FALSE(unsteadyNote({}).has_value());
  EXPECT_FALSE(unsteadyNote({{"a", {10, 11, 19.9}}, {"b", {20, 39}}, {"c", {5}}}).has_value());
  const auto note =
      unsteadyNote({{"a", {10, 11, 21}}, {"bonsai 512² mip", {40, 90, 41}}, {"c", {5, 5}}});
  ASSERT_TRUE(note.has_value());
  EXPECT_NE(note->find("UNSTEADY RUN: frame times of one case spread up to 2.25x "
                       "(bonsai 512² mip: 40.0 to 90.0 ms; 2 of 3 cases past 2.0x)"),
            std::string::npos)
      << *note;
  // One case alone, a frame of 0 ms (no measure) not counted; frames of a few milliseconds
  // swing 2x from the scheduler alone.
  EXPECT_FALSE(unsteadyNote({{"a", {0, 30}}}).has_value());
  EXPECT_FALSE(unsteadyNote({{"64² mip", {2, 4.5, 6}}}).has_value());
}

}  // namespace
}  // namespace vsil::bench
