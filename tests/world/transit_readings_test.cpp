// Readings while moving (issue 47, WorldOptions::read_while_moving): the sensor reads at its own
// rate along every path, each reading recorded with its point and time; the sensor's lag is in
// them, their noise comes from a stream of its own, and the stops read what they read without.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <thread>
#include <vector>

#include "support/axis_plume.hpp"
#include "world/shared_plume.hpp"
#include "world/simulated_world.hpp"

namespace plumekit::ste {
namespace {

// The axis plume (test::AxisPlume), its robot reading on the way unless told.
struct PlumeWorld : test::AxisPlume {
  world::WorldOptions options(const std::string& sensor, bool read_while_moving = true) const {
    world::WorldOptions o = quick_options(sensor);
    o.read_while_moving = read_while_moving;
    return o;
  }
  world::SimulatedWorld make(const world::WorldOptions& o, std::uint64_t seed = 31) const {
    return world::SimulatedWorld(map, wind, source, o, seed);
  }
};

// Across the plume, 3 m downwind of the source: 6.06 s at 0.5 m/s, not a whole number of
// reading intervals, so a rest is waited at the end.
const std::vector<Vec2> kAcross{{5.0, 0.3}, {5.0, 3.7}};
constexpr double kAcrossMetres = 3.03;
// Along the plume's axis from clean air upwind of the source into the plume.
const std::vector<Vec2> kEntering{{0.5, 2.0}, {4.5, 2.0}};
constexpr double kEnteringMetres = 4.03;

void expect_same(const std::vector<world::TransitReading>& a,
                 const std::vector<world::TransitReading>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) {
    EXPECT_EQ(a[k].position.x, b[k].position.x) << "reading " << k;
    EXPECT_EQ(a[k].position.y, b[k].position.y) << "reading " << k;
    EXPECT_EQ(a[k].recorded.x, b[k].recorded.x) << "reading " << k;
    EXPECT_EQ(a[k].recorded.y, b[k].recorded.y) << "reading " << k;
    EXPECT_EQ(a[k].time_s, b[k].time_s) << "reading " << k;
    EXPECT_EQ(a[k].value, b[k].value) << "reading " << k;
  }
}

void expect_same(const world::Reading& a, const world::Reading& b) {
  EXPECT_EQ(a.gas, b.gas);
  EXPECT_EQ(a.wind.x, b.wind.x);
  EXPECT_EQ(a.wind.y, b.wind.y);
  EXPECT_EQ(a.wind_variance, b.wind_variance);
  EXPECT_EQ(a.position.x, b.position.x);
  EXPECT_EQ(a.position.y, b.position.y);
}

TEST(TransitReadings, TheIdealSensorReadsThePlumeAtEachIntervalsPointAndTime) {
  const PlumeWorld w;
  world::SimulatedWorld moving = w.make(w.options("ideal"));
  EXPECT_TRUE(moving.reads_while_travelling());
  const double t0 = moving.time(), interval = moving.reading_interval();
  const double speed = moving.options().speed, seconds = kAcrossMetres / speed;
  moving.travel(kAcross, kAcrossMetres);
  const std::vector<world::TransitReading> readings = moving.take_transit_readings();
  ASSERT_EQ(readings.size(), static_cast<std::size_t>(std::floor(seconds / interval)));
  EXPECT_TRUE(moving.take_transit_readings().empty());  // taken: forgotten
  EXPECT_NEAR(moving.time(), t0 + seconds, moving.options().filament.dt);

  // The reference: a robot of the same seed that stops for one reading at each point, at the
  // same moment (a stop reads now, then lets one interval pass).
  world::WorldOptions one_reading = w.options("ideal", false);
  one_reading.sample_s = interval;
  world::SimulatedWorld stopping = w.make(one_reading);
  stopping.wait(interval);
  double most = 0.0;
  for (std::size_t k = 0; k < readings.size(); ++k) {
    const world::TransitReading& r = readings[k];
    const double elapsed = static_cast<double>(k + 1) * interval;
    EXPECT_NEAR(r.time_s, t0 + elapsed, 1e-9) << "reading " << k;
    if (k > 0) {
      EXPECT_NEAR(r.time_s - readings[k - 1].time_s, interval, 1e-9) << "reading " << k;
    }
    EXPECT_NEAR(r.position.x, 5.0, 1e-12) << "reading " << k;
    EXPECT_NEAR(r.position.y, 0.3 + speed * elapsed, 1e-9) << "reading " << k;
    EXPECT_EQ(r.recorded.x, r.position.x);  // no position noise, no odometry
    EXPECT_EQ(r.recorded.y, r.position.y);
    EXPECT_EQ(stopping.time(), r.time_s) << "reading " << k;
    EXPECT_EQ(stopping.stop(r.position).gas, r.value) << "reading " << k;
    most = std::max(most, r.value);
  }
  EXPECT_GT(most, 1.0);  // the path crossed the plume
}

TEST(TransitReadings, NothingIsRecordedWithTheOptionOff) {
  const PlumeWorld w;
  for (const std::string sensor : {"ideal", "mox-fast"}) {
    world::SimulatedWorld world = w.make(w.options(sensor, false));
    EXPECT_EQ(world.reads_while_travelling(), sensor != "ideal");
    world.travel(kAcross, kAcrossMetres);
    world.pass(kAcross, 0.5);
    EXPECT_TRUE(world.take_transit_readings().empty()) << sensor;
  }
}

// The option only records: the stops' draws (gas noise, anemometer, position, odometry) and the
// plume they read are those of the world without it.
TEST(TransitReadings, TheOptionLeavesTheStopsAsTheyWere) {
  const PlumeWorld w;
  for (const std::string sensor : {"ideal", "mox-fast"}) {
    SCOPED_TRACE(sensor);
    std::vector<world::WorldOptions> options;
    for (bool on : {false, true}) {
      world::WorldOptions o = w.options(sensor, on);
      o.noise = 2.0;
      o.wind_direction_noise_deg = 10.0;
      o.wind_variance_noise_deg = 20.0;
      o.position_noise = 0.2;
      o.odometry_drift = 0.05;
      options.push_back(o);
    }
    world::SimulatedWorld off = w.make(options[0]), on = w.make(options[1]);
    for (world::SimulatedWorld* world : {&off, &on}) {
      world->stop({4.0, 1.0});
      world->travel(kAcross, kAcrossMetres);
    }
    expect_same(off.stop(kAcross.back()), on.stop(kAcross.back()));
    for (world::SimulatedWorld* world : {&off, &on})
      world->travel({kAcross.back(), {8.0, 2.0}}, 3.53);
    expect_same(off.stop({8.0, 2.0}), on.stop({8.0, 2.0}));
    EXPECT_EQ(off.time(), on.time());
    EXPECT_EQ(off.steps(), on.steps());
    EXPECT_EQ(on.take_transit_readings().size(), 60u + 70u);  // 6.06 s and 7.06 s at 10 Hz
  }
}

// The MOX sensor's response is in the record: what it reads on the way is the ideal readings
// through its model, so entering the plume from clean air it reads less than the gas there.
TEST(TransitReadings, AMoxSensorsReadingsLagTheIdealOnes) {
  const PlumeWorld w;
  world::SimulatedWorld ideal_world = w.make(w.options("ideal")),
                        mox_world = w.make(w.options("mox-fast"));
  for (world::SimulatedWorld* world : {&ideal_world, &mox_world})
    world->travel(kEntering, kEnteringMetres);
  const std::vector<world::TransitReading> ideal = ideal_world.take_transit_readings(),
                                           mox = mox_world.take_transit_readings();
  ASSERT_EQ(mox.size(), ideal.size());
  world::GasSensor sensor(world::gas_sensor_preset("mox-fast"), ideal_world.reading_interval());
  std::size_t entered = ideal.size();
  for (std::size_t k = 0; k < ideal.size(); ++k) {
    EXPECT_EQ(mox[k].time_s, ideal[k].time_s);
    EXPECT_EQ(mox[k].position.y, ideal[k].position.y);
    EXPECT_EQ(mox[k].value, sensor.read(ideal[k].value)) << "reading " << k;
    if (entered == ideal.size() && ideal[k].value > 0.0) entered = k;
  }
  ASSERT_LT(entered, ideal.size());
  ASSERT_GT(entered, 0u);  // from clean air
  EXPECT_LT(mox[entered].value, 0.9 * ideal[entered].value);
  EXPECT_GT(mox[entered].value, 0.0);
}

// travel() is pass() for each whole reading interval, then a wait for the rest: a team's robot,
// which moves by pass(), records what a lone robot does.
TEST(TransitReadings, TravelIsPassAtEachIntervalThenAWait) {
  const PlumeWorld w;
  world::WorldOptions o = w.options("mox-fast");
  o.noise = 1.0;
  o.position_noise = 0.1;
  const std::vector<Vec2> bent{{9.0, 0.5}, {6.0, 2.0}, {4.0, 3.0}};
  const double metres = norm(bent[1] - bent[0]) + norm(bent[2] - bent[1]);
  world::SimulatedWorld travelling = w.make(o), passing = w.make(o);
  travelling.travel(bent, metres);
  const double seconds = metres / o.speed, interval = passing.reading_interval();
  const int n = static_cast<int>(std::floor(seconds / interval));
  for (int k = 1; k <= n; ++k)
    passing.pass(bent, k * interval * o.speed);
  passing.wait(seconds - n * interval);
  const std::vector<world::TransitReading> travelled = travelling.take_transit_readings();
  EXPECT_EQ(travelled.size(), static_cast<std::size_t>(n));
  expect_same(travelled, passing.take_transit_readings());
  EXPECT_EQ(travelling.time(), passing.time());
  EXPECT_EQ(travelling.steps(), passing.steps());
  expect_same(travelling.stop(bent.back()), passing.stop(bent.back()));
}

TEST(TransitReadings, NoiseIsClippedAtZeroAndTheSameForASeed) {
  const PlumeWorld w;
  world::WorldOptions noisy = w.options("ideal");
  noisy.noise = 2.0;
  std::vector<std::vector<world::TransitReading>> runs;
  for (const world::WorldOptions& o : {noisy, noisy, w.options("ideal")}) {
    world::SimulatedWorld world = w.make(o);
    world.travel(kEntering, kEnteringMetres);
    runs.push_back(world.take_transit_readings());
  }
  expect_same(runs[0], runs[1]);
  const std::vector<world::TransitReading>&with = runs[0], &without = runs[2];
  ASSERT_EQ(with.size(), without.size());
  std::size_t differ = 0, clipped = 0;
  for (std::size_t k = 0; k < with.size(); ++k) {
    EXPECT_GE(with[k].value, 0.0);
    EXPECT_EQ(with[k].time_s, without[k].time_s);  // the noise is not the plume's
    differ += with[k].value != without[k].value;
    clipped += with[k].value == 0.0;
  }
  EXPECT_GT(differ, with.size() / 2);
  EXPECT_GT(clipped, 0u);  // clean air plus noise below 0 reads 0
}

// The recorded point is the true one plus a fix's error (std position_noise per axis) and the
// odometry's drift so far along the leg.
TEST(TransitReadings, TheRecordedPointCarriesTheFixErrorAndTheDriftSoFar) {
  const PlumeWorld w;
  world::WorldOptions fixes = w.options("ideal");
  fixes.position_noise = 0.3;
  world::SimulatedWorld world = w.make(fixes);
  for (int leg = 0; leg < 10; ++leg)
    world.travel(leg % 2 == 0 ? kAcross : std::vector<Vec2>{kAcross[1], kAcross[0]}, kAcrossMetres);
  const std::vector<world::TransitReading> readings = world.take_transit_readings();
  double sum2 = 0.0;
  for (const world::TransitReading& r : readings)
    sum2 += std::pow(r.recorded.x - r.position.x, 2) + std::pow(r.recorded.y - r.position.y, 2);
  // 600 readings, 1200 errors: the std within 10 % (the walls' redraws barely trim it).
  EXPECT_NEAR(std::sqrt(sum2 / (2.0 * static_cast<double>(readings.size()))), 0.3, 0.03);

  // Odometry alone: the drift grows from the leg's start to its end, where the stop records it.
  world::WorldOptions drift = w.options("ideal");
  drift.odometry_drift = 0.2;
  world::SimulatedWorld drifting = w.make(drift);
  drifting.travel(kAcross, kAcrossMetres);
  const std::vector<world::TransitReading> leg = drifting.take_transit_readings();
  const world::Reading end = drifting.stop(kAcross.back());
  const Vec2 total = end.position - kAcross.back();
  ASSERT_GT(norm(total), 0.0);
  for (const world::TransitReading& r : leg) {
    const double share = (r.position.y - kAcross[0].y) / kAcrossMetres;
    EXPECT_NEAR(r.recorded.x - r.position.x, share * total.x, 1e-9);
    EXPECT_NEAR(r.recorded.y - r.position.y, share * total.y, 1e-9);
  }
}

// In a plume several robots share, each on its own thread, a robot records what it records alone.
TEST(TransitReadings, ARobotInASharedPlumeRecordsWhatItRecordsAlone) {
  const PlumeWorld w;
  const std::vector<std::string> sensors{"ideal", "mox-fast"};
  const std::uint64_t seed = 31;
  const auto mission = [&](world::SimulatedWorld& world, std::size_t r) {
    world.stop({4.0, 1.0 + static_cast<double>(r)});
    world.travel(kAcross, kAcrossMetres - 0.4 * static_cast<double>(r));
    world.stop({5.0, 3.0});
    return world.take_transit_readings();
  };
  std::vector<std::vector<world::TransitReading>> alone, shared(sensors.size());
  for (std::size_t r = 0; r < sensors.size(); ++r) {
    world::SimulatedWorld world = w.make(w.options(sensors[r]), seed);
    alone.push_back(mission(world, r));
  }
  world::SharedPlume plume(w.map, w.wind, w.source, w.options("ideal").filament, seed, 2);
  std::vector<std::thread> robots;
  for (std::size_t r = 0; r < sensors.size(); ++r)
    robots.emplace_back([&, r] {
      world::SimulatedWorld world(plume, static_cast<int>(r), w.map, w.source,
                                  w.options(sensors[r]), seed);
      shared[r] = mission(world, r);
    });
  for (std::thread& t : robots)
    t.join();
  for (std::size_t r = 0; r < sensors.size(); ++r) {
    SCOPED_TRACE(sensors[r]);
    EXPECT_FALSE(alone[r].empty());
    expect_same(shared[r], alone[r]);
  }
}

}  // namespace
}  // namespace plumekit::ste
