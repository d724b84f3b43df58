// The gas sensor's response against the closed forms of seed 000's model
// (Eqs. 4.5-4.9, Table 4.1) and seed 004's MiCS-5521 times.
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.hpp"
#include "world/gas_sensor.hpp"

namespace plumekit::dataset {
namespace {

// Seconds until the reading first crosses `level`, feeding `input` every dt.
double time_to(world::GasSensor& sensor, double input, double level, bool rising, double dt,
               double limit = 300.0) {
  for (double t = dt; t < limit; t += dt) {
    const double r = sensor.read(input);
    if (rising ? r >= level : r <= level) return t;
  }
  return -1.0;
}

TEST(GasSensor, TheIdealSensorReadsTheConcentration) {
  world::GasSensor ideal(world::gas_sensor_preset("ideal"), 0.1);
  EXPECT_FALSE(ideal.has_memory());
  for (const double c : {0.0, 12.5, 3000.0, 0.0})
    EXPECT_EQ(ideal.read(c), c);
}

TEST(GasSensor, CatalyticAndElectrochemicalStepsMatchTable41) {
  const double dt = 0.01, ln10 = std::log(10.0);
  for (const char* name : {"catalytic", "electrochemical"}) {
    const world::GasSensorModel m = world::gas_sensor_preset(name);
    world::GasSensor up(m, dt);
    // Nothing for the rise's dead time, then 90 % after tau_r ln 10 more.
    EXPECT_NEAR(time_to(up, 1.0, 1e-9, true, dt), m.dead_rise_s + dt, 1e-6) << name;
    world::GasSensor rise(m, dt);
    EXPECT_NEAR(time_to(rise, 1.0, 0.9, true, dt), m.dead_rise_s + m.rise_s * ln10, 2 * dt) << name;
    // Saturated, then clean air: the decay's dead time, then 10 % after tau_d ln 10.
    world::GasSensor fall(m, dt);
    for (int k = 0; k < 50000; ++k)
      fall.read(1.0);
    EXPECT_NEAR(time_to(fall, 0.0, 0.1, false, dt), m.dead_decay_s + m.decay_s * ln10, 2 * dt)
        << name;
  }
  EXPECT_EQ(world::gas_sensor_preset("catalytic").rise_s, 7.0126);
  EXPECT_EQ(world::gas_sensor_preset("electrochemical").dead_rise_s, 10.0);
}

TEST(GasSensor, InfraredRiseHasAFastAndASlowPart) {
  const double dt = 0.05;
  const world::GasSensorModel m = world::gas_sensor_preset("infrared");
  world::GasSensor ir(m, dt);
  double t = 0.0;
  for (int k = 1; k <= 1200; ++k) {
    const double r = ir.read(1.0);
    t = k * dt;
    const double s = t - m.dead_rise_s;  // Eq. 4.6 after the dead time
    const double expected = s <= 0.0
                                ? 0.0
                                : m.fast_share * (1.0 - std::exp(-s / m.rise_s)) +
                                      (1.0 - m.fast_share) * (1.0 - std::exp(-s / m.rise_slow_s));
    ASSERT_NEAR(r, expected, 1e-9) << "t = " << t;
  }
  EXPECT_NEAR(m.fast_share, 0.8312, 0.0);
}

TEST(GasSensor, FastMoxMatchesTheMics5521) {
  const double dt = 0.001;
  world::GasSensor rise(world::gas_sensor_preset("mox-fast"), dt);
  EXPECT_NEAR(time_to(rise, 1.0, 0.9, true, dt), 0.13, 2 * dt);
  world::GasSensor fall(world::gas_sensor_preset("mox-fast"), dt);
  for (int k = 0; k < 5000; ++k)
    fall.read(1.0);
  EXPECT_NEAR(time_to(fall, 0.0, 0.1, false, dt), 0.41, 2 * dt);
}

// The point: a 5 s stop at 10 Hz, arriving from clean air, with a slow sensor.
TEST(GasSensor, AFiveSecondStopWithASlowSensorReadsFarLessThanTheTruth) {
  for (const char* name : {"catalytic", "electrochemical", "infrared", "mox-fast"}) {
    world::GasSensor s(world::gas_sensor_preset(name), 0.1);
    double sum = 0.0;
    for (int k = 0; k < 50; ++k)
      sum += s.read(100.0);
    const double mean = sum / 50;
    if (std::string(name) == "mox-fast")
      EXPECT_GT(mean, 95.0) << name;
    else
      EXPECT_LT(mean, 10.0) << name;  // the dead times alone take 4-10 s
  }
}

TEST(GasSensor, BaselineIsAddedAndBadSettingsNameTheirField) {
  world::GasSensorModel m;
  m.baseline = 2.5;
  world::GasSensor s(m, 0.1);
  EXPECT_EQ(s.read(10.0), 12.5);
  try {
    world::gas_sensor_preset("tgs9999");
    FAIL() << "an unknown preset was accepted";
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "sensor.gas");
    EXPECT_NE(e.message().find("mox-fast"), std::string::npos) << e.message();
  }
  m.decay_s = -1.0;
  EXPECT_THROW(world::GasSensor(m, 0.1), OptionError);
  m.decay_s = std::nan("");
  EXPECT_THROW(world::GasSensor(m, 0.1), OptionError);
}

}  // namespace
}  // namespace plumekit::dataset
