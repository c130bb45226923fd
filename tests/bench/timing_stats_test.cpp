// The bench's ratio of two cases from paired frames (harness/timing_stats.h pairedRatio).
#include <cmath>
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

}  // namespace
}  // namespace vsil::bench
