#include "core/statistics.hpp"

#include <gtest/gtest.h>

namespace plumekit {
namespace {

TEST(Statistics, MedianOfOddAndEvenCounts) {
  EXPECT_EQ(median({3.0, 1.0, 2.0}), 2.0);
  EXPECT_EQ(median({4.0, 1.0, 3.0, 2.0}), 2.5);
  EXPECT_EQ(median({}), 0.0);
  EXPECT_EQ(median({7.0}), 7.0);
}

TEST(Statistics, PercentileInterpolatesBetweenOrderStatistics) {
  const std::vector<double> v{10, 0, 30, 20};  // sorted: 0 10 20 30, ranks 0..3
  EXPECT_EQ(percentile(v, 0.0), 0.0);
  EXPECT_EQ(percentile(v, 1.0), 30.0);
  EXPECT_DOUBLE_EQ(percentile(v, 0.25), 7.5);  // rank 0.75
  EXPECT_DOUBLE_EQ(percentile(v, 0.5), median(v));
  EXPECT_EQ(percentile(v, 2.0), 30.0);  // clamped
  EXPECT_EQ(percentile({}, 0.5), 0.0);
}

// The 95 % Wilson score interval against Newcombe (1998), "Two-sided confidence intervals for
// the single proportion", Table I, method 3 (score, no continuity correction).
TEST(Statistics, WilsonIntervalMatchesPublishedValues) {
  const struct {
    int k, n;
    double lo, hi;
  } table[] = {{81, 263, 0.2553, 0.3662},
               {15, 148, 0.0624, 0.1605},
               {0, 20, 0.0, 0.1611},
               {1, 29, 0.0061, 0.1718}};
  for (const auto& row : table) {
    const Interval i = wilson_interval(row.k, row.n);
    EXPECT_NEAR(i.lo, row.lo, 6e-5) << row.k << "/" << row.n;
    EXPECT_NEAR(i.hi, row.hi, 6e-5) << row.k << "/" << row.n;
  }
  EXPECT_EQ(wilson_interval(0, 20).lo, 0.0);  // not below 0, and 0/20 is not a point
  EXPECT_EQ(wilson_interval(20, 20).hi, 1.0);
  const Interval big = wilson_interval(491, 540);  // an evaluation's size: about +-2.5 points
  EXPECT_LT(big.lo, 491.0 / 540.0);
  EXPECT_GT(big.hi, 491.0 / 540.0);
  EXPECT_NEAR(big.hi - big.lo, 0.049, 0.002);
  const Interval empty = wilson_interval(0, 0);
  EXPECT_EQ(empty.lo, 0.0);
  EXPECT_EQ(empty.hi, 1.0);
}

}  // namespace
}  // namespace plumekit
