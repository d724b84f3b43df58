// One plume that several robots sample in one world clock (world/shared_plume.hpp): each robot,
// on its own thread, reads exactly what it reads in a world of its own with the same seed.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>
#include <vector>

#include "core/error.hpp"
#include "support/axis_plume.hpp"
#include "world/shared_plume.hpp"
#include "world/simulated_world.hpp"

namespace plumekit::ste {
namespace {

// The axis plume in the faithful world (unsteady wind, occlusion), with wind and position noise.
struct PlumeWorld : test::AxisPlume {
  std::uint64_t seed = 29;
  world::WorldOptions options(const std::string& sensor) const {
    world::WorldOptions o = quick_options(sensor);
    o.wind_direction_noise_deg = 10.0;
    o.position_noise = 0.1;
    return o;
  }
};

// What a robot did: every reading and its clock after each action.
struct Log {
  std::vector<world::Reading> readings;
  std::vector<double> times;
};

// A mission of `stops` stops along the plume, travelling `metres` between them (not multiples of
// the plume's dt, so the leftover seconds carry from leg to leg).
Log mission(world::SimulatedWorld& world, int stops, double metres) {
  Log log;
  Vec2 p{3.0, 1.0};
  for (int k = 0; k < stops; ++k) {
    log.readings.push_back(world.stop(p));
    log.times.push_back(world.time());
    const Vec2 next{p.x + 0.7 * metres, p.y + 0.2};
    world.travel({p, next}, metres);
    log.times.push_back(world.time());
    p = next;
  }
  return log;
}

void expect_same(const Log& a, const Log& b) {
  ASSERT_EQ(a.readings.size(), b.readings.size());
  for (std::size_t k = 0; k < a.readings.size(); ++k) {
    EXPECT_EQ(a.readings[k].gas, b.readings[k].gas) << "stop " << k;
    EXPECT_EQ(a.readings[k].wind.x, b.readings[k].wind.x) << "stop " << k;
    EXPECT_EQ(a.readings[k].wind.y, b.readings[k].wind.y) << "stop " << k;
    EXPECT_EQ(a.readings[k].wind_variance, b.readings[k].wind_variance) << "stop " << k;
    EXPECT_EQ(a.readings[k].position.x, b.readings[k].position.x) << "stop " << k;
    EXPECT_EQ(a.readings[k].position.y, b.readings[k].position.y) << "stop " << k;
  }
  EXPECT_EQ(a.times, b.times);
}

TEST(SharedPlume, RobotsOnThreadsReadWhatEachReadsAlone) {
  const PlumeWorld w;
  // Three robots with their own paces and sensors; the first leaves long before the others.
  const std::vector<std::string> sensors{"ideal", "catalytic", "mox-fast"};
  const std::vector<int> stops{2, 6, 5};
  const std::vector<double> legs{1.3, 0.77, 1.01};
  std::vector<Log> alone;
  for (std::size_t r = 0; r < sensors.size(); ++r) {
    world::SimulatedWorld world(w.map, w.wind, w.source, w.options(sensors[r]), w.seed);
    alone.push_back(mission(world, stops[r], legs[r]));
  }
  world::SharedPlume plume(w.map, w.wind, w.source, w.options("ideal").filament, w.seed, 3);
  std::vector<Log> shared(sensors.size());
  std::vector<std::thread> robots;
  for (std::size_t r = 0; r < sensors.size(); ++r)
    robots.emplace_back([&, r] {
      world::SimulatedWorld world(plume, static_cast<int>(r), w.map, w.source,
                                  w.options(sensors[r]), w.seed);
      shared[r] = mission(world, stops[r], legs[r]);
    });
  for (std::thread& t : robots)
    t.join();
  for (std::size_t r = 0; r < sensors.size(); ++r) {
    SCOPED_TRACE(sensors[r]);
    expect_same(shared[r], alone[r]);
  }
  // The readings are of a plume, not of nothing.
  EXPECT_GT(alone[1].readings.back().gas + alone[2].readings.back().gas, 0.0);
}

TEST(SharedPlume, ARobotRunsAheadByAtMostTheRingOfFramesAndReadsTheSamePlume) {
  const PlumeWorld w;
  const world::FilamentOptions o = w.options("ideal").filament;
  world::SharedPlume plume(w.map, w.wind, w.source, o, w.seed, 2);
  world::SharedPlume alone(w.map, w.wind, w.source, o, w.seed, 1);
  const long long ring = plume.ring_size();
  ASSERT_GE(ring, 2);
  const long long far = ring + 50;
  const Vec2 p{4.0, 2.0};
  std::atomic<bool> done{false};
  double read_far = -1.0;
  std::thread ahead([&] {
    read_far = plume.at(far, 0).concentration_at(p);
    done = true;
    plume.leave(0);
  });
  // Robot 0 cannot have its frame while robot 1 may still read the one it would overwrite.
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  EXPECT_FALSE(done);
  const double read_near = plume.at(60, 1).concentration_at(p);  // room for robot 0 now
  ahead.join();
  EXPECT_TRUE(done);
  EXPECT_EQ(read_near, alone.at(60, 0).concentration_at(p));
  EXPECT_EQ(read_far, alone.at(far, 0).concentration_at(p));
  EXPECT_GT(read_far, 0.0);
}

TEST(SharedPlume, ARobotsStepsNeverGoBack) {
  const PlumeWorld w;
  world::SharedPlume plume(w.map, w.wind, w.source, w.options("ideal").filament, w.seed, 1);
  const double t0 = plume.at(0, 0).time();
  EXPECT_DOUBLE_EQ(plume.at(4, 0).time(), t0 + 4 * w.options("ideal").filament.dt);
  EXPECT_THROW(plume.at(3, 0), std::logic_error);
}

TEST(SharedPlume, ARobotWhoseOptionsFailDoesNotHoldTheOthers) {
  const PlumeWorld w;
  world::SharedPlume plume(w.map, w.wind, w.source, w.options("ideal").filament, w.seed, 2);
  world::WorldOptions bad = w.options("ideal");
  bad.speed = -1.0;
  EXPECT_THROW(world::SimulatedWorld(plume, 1, w.map, w.source, bad, w.seed), OptionError);
  world::SimulatedWorld world(plume, 0, w.map, w.source, w.options("ideal"), w.seed);
  world.travel({}, 3.0);  // 6 s: the plume steps on without robot 1
  world.stop({4.0, 2.0});
  EXPECT_NEAR(world.time() - plume.spinup_s(), 6.0 + 5.0, 1e-9);
}

}  // namespace
}  // namespace plumekit::ste
