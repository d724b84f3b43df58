#include "methods/wind_statistics.hpp"

#include <gtest/gtest.h>

namespace plumekit::methods {
namespace {

TEST(WindStatistics, SteadyDirectionHasNoVariance) {
  const auto s = circular_statistics({0.3, 0.3, 0.3});
  EXPECT_NEAR(s.mean, 0.3, 1e-12);
  EXPECT_NEAR(s.variance, 0.0, 1e-12);
}

TEST(WindStatistics, MeanCrossesTheBranchCut) {
  // 170 and -170 degrees average to 180, not 0.
  const auto s = circular_statistics({radians(170.0), radians(-170.0)});
  EXPECT_NEAR(std::abs(s.mean), kPi, 1e-12);
  EXPECT_NEAR(s.variance, 1.0 - std::cos(radians(10.0)), 1e-12);
}

TEST(WindStatistics, OppositeDirectionsHaveFullVariance) {
  EXPECT_NEAR(circular_statistics({0.0, kPi}).variance, 1.0, 1e-12);
  EXPECT_NEAR(circular_statistics({}).variance, 1.0, 0.0);
}

TEST(WindStatistics, UpwindAndRotation) {
  const Vec2 u = upwind({0.5, 0.0});
  EXPECT_NEAR(u.x, -1.0, 1e-15);
  EXPECT_NEAR(u.y, 0.0, 1e-15);
  const Vec2 r = rotate({1.0, 0.0}, kPi / 2);
  EXPECT_NEAR(r.x, 0.0, 1e-15);
  EXPECT_NEAR(r.y, 1.0, 1e-15);
  EXPECT_EQ(upwind({0.0, 0.0}).x, 0.0);
  EXPECT_NEAR(wrap_angle(3 * kPi), kPi, 1e-12);
  EXPECT_NEAR(wrap_angle(-kPi), kPi, 1e-12);
}

}  // namespace
}  // namespace plumekit::methods
