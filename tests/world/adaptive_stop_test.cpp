// Adaptive stops (issue 47, WorldOptions::adaptive_stop): a stop ends once its mean is settled,
// between stop_min_s and sample_s, and its reading is then the mean of the readings it took.
#include <gtest/gtest.h>

#include "support/axis_plume.hpp"
#include "world/simulated_world.hpp"

namespace plumekit::world {
namespace {

// The axis plume (test::AxisPlume), its stops adaptive or not.
struct PlumeWorld : test::AxisPlume {
  WorldOptions options(bool adaptive) const {
    WorldOptions o = quick_options();
    o.adaptive_stop = adaptive;
    return o;
  }
  SimulatedWorld make(const WorldOptions& o) const {
    return SimulatedWorld(map, wind, source, o, 31);
  }
};

// Runs a stop at p; returns its reading and how long it lasted.
std::pair<Reading, double> timed_stop(SimulatedWorld& w, Vec2 p) {
  const double t0 = w.time();
  const Reading r = w.stop(p);
  return {r, w.time() - t0};
}

TEST(AdaptiveStop, InCleanAirAStopLastsItsMinimum) {
  const PlumeWorld pw;
  WorldOptions o = pw.options(true);
  SimulatedWorld w = pw.make(o);
  const auto [reading, seconds] = timed_stop(w, {1.0, 0.5});  // upwind of the source
  EXPECT_EQ(reading.gas, 0.0);
  EXPECT_NEAR(seconds, o.stop_min_s, 1e-9);
}

TEST(AdaptiveStop, WhereThePlumeComesAndGoesAStopLastsUntilItsMeanSettles) {
  const PlumeWorld pw;
  // No tolerance: the plume's readings never settle, so the stop lasts the whole sample_s.
  WorldOptions strict = pw.options(true);
  strict.stop_tolerance = 0.0;
  SimulatedWorld a = pw.make(strict);
  const auto [in_plume, seconds] = timed_stop(a, {5.0, 2.0});
  EXPECT_GT(in_plume.gas, 0.0);
  EXPECT_NEAR(seconds, strict.sample_s, 1e-9);
  // Any tolerance: the stop ends at its minimum, and reads what a stop of that length reads.
  WorldOptions loose = pw.options(true);
  loose.stop_min_s = 2.0;
  loose.stop_tolerance = 1e9;
  WorldOptions two = pw.options(false);
  two.sample_s = 2.0;
  SimulatedWorld b = pw.make(loose), c = pw.make(two);
  const auto [early, early_s] = timed_stop(b, {5.0, 2.0});
  const auto [fixed, fixed_s] = timed_stop(c, {5.0, 2.0});
  EXPECT_NEAR(early_s, 2.0, 1e-9);
  EXPECT_EQ(early.gas, fixed.gas);
  EXPECT_EQ(early.wind.x, fixed.wind.x);
  EXPECT_EQ(early.wind_variance, fixed.wind_variance);
  // A tolerance in between: longer than the minimum, no longer than sample_s, whole seconds.
  WorldOptions mid = pw.options(true);
  mid.stop_tolerance = 0.1 * in_plume.gas;
  SimulatedWorld d = pw.make(mid);
  const double mid_s = timed_stop(d, {5.0, 2.0}).second;
  EXPECT_GE(mid_s, mid.stop_min_s - 1e-9);
  EXPECT_LE(mid_s, mid.sample_s + 1e-9);
  EXPECT_NEAR(mid_s, std::round(mid_s), 1e-9);
}

TEST(AdaptiveStop, BadOptionsNameTheirField) {
  WorldOptions o;
  o.stop_min_s = 0.0;
  try {
    o.validate();
    FAIL() << "a stop of no length was taken";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("ste.world.stop_min_s"), std::string::npos) << e.what();
  }
  o = {};
  o.stop_tolerance = -1.0;
  EXPECT_THROW(o.validate(), std::exception);
}

}  // namespace
}  // namespace plumekit::world
