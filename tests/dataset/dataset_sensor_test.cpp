// A dataset's static sensors read through a gas sensor (issue 18): a settled
// sensor keeps reading what it is in, the record with a sensor is what that
// sensor reads (a slow one smooths the fluctuations away), a baseline is an
// exact offset, and a steady plume model refuses a sensor with a response.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "core/error.hpp"
#include "dataset/plume.hpp"
#include "support/uniform_wind.hpp"
#include "world/filament_model.hpp"

namespace plumekit::dataset {
namespace {

TEST(GasSensor, ASettledSensorKeepsReadingWhatItIsIn) {
  for (const std::string name : {"catalytic", "electrochemical", "infrared", "mox-fast"}) {
    world::GasSensor s(world::gas_sensor_preset(name), 0.1);
    s.settle(250.0);
    for (int k = 0; k < 100; ++k)
      ASSERT_NEAR(s.read(250.0), 250.0, 1e-9) << name;
  }
  EXPECT_EQ(world::gas_sensor_preset("ideal").settling_s(), 0.0);
  EXPECT_NEAR(world::gas_sensor_preset("catalytic").settling_s(), 5.0 + 5 * 7.0126, 1e-9);
}

TEST(DatasetSensor, TheRecordIsWhatTheSensorReads) {
  const Map map = default_arena(10.0, 4.0);
  const cfd::WindField wind = test::uniform_wind(10.0, 4.0, 0.05, 1.0);
  world::FilamentOptions o;
  // The steady wind's uniform 1 s meander, on which the bounds below were set (in the unsteady
  // field the catalytic sensor keeps 34 % of the ideal std on this centreline).
  o.unsteady_wind = false;
  o.max_spinup = 20.0;
  const GridShape sensors{64, 64, 10.0, 4.0};
  const Vec2 source{1.0, 2.0};
  const world::SensorRecord ideal = world::simulate_filaments(map, wind, source, sensors, o, 9);
  EXPECT_EQ(ideal.summary.sensor_warmup_s, 0.0);
  world::GasSensorModel offset;
  offset.baseline = 40.0;
  const world::SensorRecord shifted =
      world::simulate_filaments(map, wind, source, sensors, o, 9, offset);
  for (std::size_t k = 0; k < ideal.mean.values.size(); ++k) {
    ASSERT_NEAR(shifted.mean.values[k], ideal.mean.values[k] + 40.0, 1e-9);
    ASSERT_NEAR(shifted.std.values[k], ideal.std.values[k], 1e-6);
  }
  // Along the centreline, 2 to 8 m downwind, summed.
  auto centreline = [&](const Grid<double>& g) {
    double total = 0.0;
    for (int i = 0; i < sensors.nx; ++i) {
      const double x = sensors.centre(i, 0).x;
      if (x >= 3.0 && x <= 9.0) total += g(i, 31) + g(i, 32);
    }
    return total;
  };
  const double ideal_mean = centreline(ideal.mean), ideal_std = centreline(ideal.std);
  const world::SensorRecord mox = world::simulate_filaments(map, wind, source, sensors, o, 9,
                                                            world::gas_sensor_preset("mox-fast"));
  const world::SensorRecord cat = world::simulate_filaments(map, wind, source, sensors, o, 9,
                                                            world::gas_sensor_preset("catalytic"));
  std::printf(
      "centreline mean / std: ideal %.0f / %.0f, mox-fast %.0f / %.0f, catalytic %.0f / "
      "%.0f (warm-ups %.1f s, %.1f s)\n",
      ideal_mean, ideal_std, centreline(mox.mean), centreline(mox.std), centreline(cat.mean),
      centreline(cat.std), mox.summary.sensor_warmup_s, cat.summary.sensor_warmup_s);
  // The fast MOX sensor (0.13 s to 90 %) follows the 10 Hz readings almost
  // exactly: the same mean, and most of the fluctuation.
  EXPECT_NEAR(centreline(mox.mean), ideal_mean, 0.15 * ideal_mean);
  EXPECT_GT(centreline(mox.std), 0.6 * ideal_std);
  // The catalytic one (7 s rise) averages over seconds: a fraction of the std.
  EXPECT_LT(centreline(cat.std), 0.3 * ideal_std);
  EXPECT_GT(centreline(cat.mean), 0.5 * ideal_mean);
  // Warm-ups: 5 x 0.41 s / ln 10 (0.89 s) and 5 s + 5 x 7.01 s (40.06 s), each in 0.1 s
  // frames, plus the frame the sensors settle on.
  EXPECT_NEAR(mox.summary.sensor_warmup_s, 1.0, 1e-9);
  EXPECT_NEAR(cat.summary.sensor_warmup_s, 40.2, 1e-9);
}

TEST(DatasetSensor, AdvectionDiffusionTakesABaselineButNoResponse) {
  PlumeOptions o;
  o.model = PlumeSimulator::AdvectionDiffusion;
  o.sensor.baseline = 5.0;
  EXPECT_NO_THROW(o.validate());
  o.sensor = world::gas_sensor_preset("infrared");
  try {
    o.validate();
    FAIL() << "the infrared sensor was accepted with advection-diffusion";
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "sensor.gas");
  }
}

}  // namespace
}  // namespace plumekit::dataset
