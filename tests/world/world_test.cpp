// The robot's simulated world with a gas sensor's response (issue 18): a slow
// sensor lags the plume, and it reads along the path between stops.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "core/error.hpp"
#include "support/uniform_wind.hpp"
#include "world/simulated_world.hpp"

namespace plumekit::ste {
namespace {

// A steady plume along y = 2 from a source at (2, 2) in a uniform 1 m/s wind.
struct PlumeWorld {
  Map map = default_arena(10.0, 4.0);
  cfd::WindField wind = test::uniform_wind(10.0, 4.0, 0.05, 1.0);
  world::SimulatedWorld make(const std::string& sensor, world::WorldOptions o = {},
                             std::uint64_t seed = 17) const {
    o.sensor = world::gas_sensor_preset(sensor);
    return world::SimulatedWorld(map, wind, {2.0, 2.0}, o, seed);
  }
};

TEST(SimulatedWorld, ASlowSensorLagsAndCarriesWhatThePathLeftInIt) {
  const PlumeWorld w;
  const Vec2 stop{4.0, 2.0};
  world::SimulatedWorld ideal = w.make("ideal");
  const double truth = ideal.stop(stop).gas;
  // Arriving from clean air (along y = 0.2), the catalytic sensor's 5 s dead
  // time swallows the whole 5 s stop.
  world::SimulatedWorld from_clean = w.make("catalytic");
  from_clean.travel({{9.0, 0.2}, {4.0, 0.2}, stop}, 6.8);
  const double cold = from_clean.stop(stop).gas;
  // Arriving along the plume's axis, it has been in gas for 10 s already.
  world::SimulatedWorld along_plume = w.make("catalytic");
  along_plume.travel({{9.0, 2.0}, stop}, 5.0);
  const double warm = along_plume.stop(stop).gas;
  std::printf("ideal %.1f, catalytic from clean air %.1f, along the plume %.1f\n", truth, cold,
              warm);
  EXPECT_GT(truth, 100.0);
  EXPECT_LT(cold, 0.1 * truth);
  EXPECT_GT(warm, 3.0 * cold + 0.2 * truth);
}

TEST(SimulatedWorld, TheIdealSensorDoesNotReadOnTheWay) {
  const PlumeWorld w;
  world::SimulatedWorld a = w.make("ideal"), b = w.make("ideal");
  a.travel({{9.0, 2.0}, {4.0, 2.0}}, 5.0);
  b.travel({}, 5.0);  // only the time passes, as before there were sensors
  EXPECT_EQ(a.stop({4.0, 2.0}).gas, b.stop({4.0, 2.0}).gas);
  EXPECT_EQ(a.time(), b.time());
}

// For the noise statistics, which need many worlds but no plume to speak of.
world::WorldOptions a_thin_plume() {
  world::WorldOptions o;
  o.filament.release_per_second = 10.0;
  o.filament.min_spinup = 0.0;
  o.filament.max_spinup = 1.0;
  return o;
}

// The anemometer reports the flow plus its meander, averaged over the stop;
// its direction error has the asked std, and the speed none.
TEST(SimulatedWorld, TheAnemometerAveragesTheWindAndItsDirectionErrorHasTheAskedStd) {
  const PlumeWorld w;
  world::SimulatedWorld exact = w.make("ideal");
  const Vec2 calm = exact.stop({6.0, 1.0}).wind;
  EXPECT_NEAR(calm.x, 1.0, 0.2);  // 1 m/s plus a 0.15 m/s meander, averaged over 5 s
  EXPECT_NEAR(calm.y, 0.0, 0.2);
  world::WorldOptions o = a_thin_plume();
  o.wind_noise_from_table35 = true;  // 5 s stops: 22.26 degrees
  EXPECT_DOUBLE_EQ(o.direction_noise_deg(), 22.26);
  double sum2 = 0.0;
  int n = 0;
  for (std::uint64_t seed = 1; seed <= 200; ++seed) {
    world::SimulatedWorld noisy = w.make("ideal", o, seed),
                          clean = w.make("ideal", a_thin_plume(), seed);
    const Vec2 a = noisy.stop({6.0, 1.0}).wind, b = clean.stop({6.0, 1.0}).wind;
    EXPECT_NEAR(norm(a), norm(b), 1e-12);  // the speed is exact
    const double d = std::atan2(cross(b, a), b.x * a.x + b.y * a.y) * 180.0 / 3.14159265358979;
    sum2 += d * d;
    ++n;
  }
  EXPECT_NEAR(std::sqrt(sum2 / n), 22.26, 2.5);  // 200 draws: the std within about 10 %
}

// With the unsteady wind the anemometer reads the meandering field where the
// robot is: it swings in the open and hardly at all beside a wall.
TEST(SimulatedWorld, TheUnsteadyAnemometerSwingsInTheOpenAndHardlyAtAWall) {
  const PlumeWorld w;
  world::WorldOptions o = a_thin_plume();
  o.filament.unsteady_wind = true;
  world::SimulatedWorld world = w.make("ideal", o);
  double open2 = 0.0, wall2 = 0.0, open_x = 0.0;
  const int stops = 200;
  for (int k = 0; k < stops; ++k) {
    const Vec2 open = world.stop({5.0, 2.0}).wind, wall = world.stop({5.0, 0.05}).wind;
    open2 += open.y * open.y;
    wall2 += wall.y * wall.y;
    open_x += open.x;
  }
  const double open_sd = std::sqrt(open2 / stops), wall_sd = std::sqrt(wall2 / stops);
  std::printf("crosswind std over 5 s stops: open %.3f m/s, at the wall %.4f m/s\n", open_sd,
              wall_sd);
  EXPECT_NEAR(open_x / stops, 1.0, 0.05);  // the mean is the steady flow
  // 0.15 m/s per axis with a 1 s correlation time, averaged over 5 s: about 0.085.
  EXPECT_GT(open_sd, 0.05);
  EXPECT_LT(open_sd, 0.15);
  EXPECT_LT(wall_sd, 0.2 * open_sd);
}

TEST(SimulatedWorld, PositionNoiseMovesTheRecordedPositionOnlyAndStaysInFreeSpace) {
  PlumeWorld w;
  w.map.obstacles = {{{5.0, 0.5}, {5.6, 0.5}, {5.6, 1.5}, {5.0, 1.5}}};
  world::WorldOptions o = a_thin_plume();
  o.position_noise = world::kGpsPositionNoise;  // seed 000, Eq. 4.3: 1.08 m
  double sum2 = 0.0;
  int n = 0;
  for (std::uint64_t seed = 1; seed <= 200; ++seed) {
    world::SimulatedWorld noisy = w.make("ideal", o, seed),
                          clean = w.make("ideal", a_thin_plume(), seed);
    const world::Reading a = noisy.stop({4.0, 1.0}), b = clean.stop({4.0, 1.0});
    EXPECT_EQ(a.gas, b.gas);  // the robot is where it is; only its record moves
    EXPECT_TRUE(w.map.is_free(a.position)) << to_string(a.position);
    sum2 += 0.5 * (a.position.x - 4.0) * (a.position.x - 4.0) +
            0.5 * (a.position.y - 1.0) * (a.position.y - 1.0);
    ++n;
  }
  // Clipped by the arena and the block, so a little under 1.08.
  EXPECT_GT(std::sqrt(sum2 / n), 0.7);
  EXPECT_LT(std::sqrt(sum2 / n), 1.3);
}

// Seed 000's GPS on every reading's fix: a stop of 20 readings records their mean, whose error
// is 1.08 / sqrt(20) = 0.24 m per axis.
TEST(SimulatedWorld, PositionNoisePerFixAveragesOverTheStopsReadings) {
  const PlumeWorld w;
  world::WorldOptions o = a_thin_plume();
  o.sample_s = 4.0;
  o.sample_rate = 5.0;  // 20 readings
  o.position_noise = world::kGpsPositionNoise;
  o.position_noise_per_fix = true;
  double sum2 = 0.0;
  const int stops = 300;
  for (std::uint64_t seed = 1; seed <= stops; ++seed) {
    const world::Reading a = w.make("ideal", o, seed).stop({5.0, 2.0});
    sum2 += 0.5 * ((a.position.x - 5.0) * (a.position.x - 5.0) +
                   (a.position.y - 2.0) * (a.position.y - 2.0));
  }
  // 600 squared errors: the estimated std is within about 3 % (1 sigma) of 0.242.
  EXPECT_NEAR(std::sqrt(sum2 / stops), world::kGpsPositionNoise / std::sqrt(20.0), 0.025);
}

}  // namespace
}  // namespace plumekit::ste

namespace plumekit::ste {
namespace {

// The circular variance a stop reports (issue 20): 0 in a laminar wind, and with the seeds'
// synthetic direction noise on the single readings, about 1 - exp(-sigma^2 / 2) (0.078 for
// 23.08 degrees: seed 002's S0 of about 0.075).
TEST(SimulatedWorld, CircularVarianceOfTheStopsWind) {
  const PlumeWorld w;
  world::WorldOptions o;
  world::set_world(o.filament, "neumann");  // no meander
  o.filament.min_spinup = o.filament.max_spinup = 2.0;
  o.filament.release_per_second = 10.0;  // the gas does not matter here
  o.sample_s = 20.0;
  o.sample_rate = 1.0;
  world::SimulatedWorld laminar = w.make("ideal", o);
  EXPECT_LT(laminar.stop({6.0, 1.0}).wind_variance, 1e-12);
  o.wind_variance_noise_deg = 23.08;
  world::SimulatedWorld noisy = w.make("ideal", o);
  double sum = 0.0;
  for (int k = 0; k < 100; ++k)
    sum += noisy.stop({6.0, 1.0}).wind_variance;
  EXPECT_NEAR(sum / 100, 1.0 - std::exp(-0.5 * std::pow(23.08 * kPi / 180.0, 2)), 0.01);
}

// Seed 000 §4.4's rotor disturbance (--rotor-disc): the 19 points stand for the disc, and the
// reading is the plume smoothed over it: lower on the plume's axis, higher in its flank.
TEST(SimulatedWorld, DiscPointsStandForTheDisc) {
  const Vec2 c{3.0, -1.0};
  const double r = 0.5;
  const std::vector<Vec2> points = world::disc_points(c, r);
  ASSERT_EQ(points.size(), 19u);
  Vec2 mean;
  double square = 0.0;
  for (const Vec2& q : points) {
    EXPECT_LE(norm(q - c), r);
    mean = mean + (1.0 / 19.0) * q;
    square += dot(q - c, q - c) / 19.0;
  }
  EXPECT_NEAR(mean.x, c.x, 1e-12);  // exact for a linear field
  EXPECT_NEAR(mean.y, c.y, 1e-12);
  EXPECT_NEAR(square, 0.5 * r * r, 0.005 * 0.5 * r * r);  // the disc's mean of |q - c|^2
}

TEST(SimulatedWorld, TheRotorDiscSmoothsThePlume) {
  const PlumeWorld w;
  world::WorldOptions rotor;
  rotor.rotor_disc = 0.5;
  world::SimulatedWorld point = w.make("ideal"), disc = w.make("ideal", rotor);
  double axis_point = 0.0, axis_disc = 0.0, flank_point = 0.0, flank_disc = 0.0;
  for (int k = 0; k < 10; ++k) {  // the same plume at the same times in both worlds
    axis_point += point.stop({3.0, 2.0}).gas;
    axis_disc += disc.stop({3.0, 2.0}).gas;
    flank_point += point.stop({3.0, 3.0}).gas;
    flank_disc += disc.stop({3.0, 3.0}).gas;
  }
  std::printf("axis: point %.0f, disc %.0f; flank: point %.0f, disc %.0f\n", axis_point / 10,
              axis_disc / 10, flank_point / 10, flank_disc / 10);
  EXPECT_LT(axis_disc, 0.9 * axis_point);
  EXPECT_GT(flank_disc, 1.2 * flank_point);
  world::WorldOptions bad;
  bad.rotor_disc = -1.0;
  EXPECT_THROW(w.make("ideal", bad), OptionError);
}

}  // namespace
}  // namespace plumekit::ste
