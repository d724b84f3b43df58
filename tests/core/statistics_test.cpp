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

}  // namespace
}  // namespace plumekit
