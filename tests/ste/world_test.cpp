// The robot's simulated world with a gas sensor's response (issue 18): a slow
// sensor lags the plume, and it reads along the path between stops.
#include <gtest/gtest.h>

#include <cstdio>

#include "dataset/uniform_wind.hpp"
#include "ste/world.hpp"

namespace plumekit::ste {
namespace {

// A steady plume along y = 2 from a source at (2, 2) in a uniform 1 m/s wind.
struct PlumeWorld {
  Map map = default_arena(10.0, 4.0);
  cfd::WindField wind = test::uniform_wind(10.0, 4.0, 0.05, 1.0);
  SimulatedWorld make(const std::string& sensor) const {
    WorldOptions o;
    o.sensor = dataset::gas_sensor_preset(sensor);
    return SimulatedWorld(map, wind, {2.0, 2.0}, o, 17);
  }
};

TEST(SimulatedWorld, ASlowSensorLagsAndCarriesWhatThePathLeftInIt) {
  const PlumeWorld w;
  const Vec2 stop{4.0, 2.0};
  SimulatedWorld ideal = w.make("ideal");
  const double truth = ideal.sample(stop);
  // Arriving from clean air (along y = 0.2), the catalytic sensor's 5 s dead
  // time swallows the whole 5 s stop.
  SimulatedWorld from_clean = w.make("catalytic");
  from_clean.travel({{9.0, 0.2}, {4.0, 0.2}, stop}, 6.8);
  const double cold = from_clean.sample(stop);
  // Arriving along the plume's axis, it has been in gas for 10 s already.
  SimulatedWorld along_plume = w.make("catalytic");
  along_plume.travel({{9.0, 2.0}, stop}, 5.0);
  const double warm = along_plume.sample(stop);
  std::printf("ideal %.1f, catalytic from clean air %.1f, along the plume %.1f\n", truth, cold,
              warm);
  EXPECT_GT(truth, 100.0);
  EXPECT_LT(cold, 0.1 * truth);
  EXPECT_GT(warm, 3.0 * cold + 0.2 * truth);
}

TEST(SimulatedWorld, TheIdealSensorDoesNotReadOnTheWay) {
  const PlumeWorld w;
  SimulatedWorld a = w.make("ideal"), b = w.make("ideal");
  a.travel({{9.0, 2.0}, {4.0, 2.0}}, 5.0);
  b.travel({}, 5.0);  // only the time passes, as before there were sensors
  EXPECT_EQ(a.sample({4.0, 2.0}), b.sample({4.0, 2.0}));
  EXPECT_EQ(a.time(), b.time());
}

}  // namespace
}  // namespace plumekit::ste
