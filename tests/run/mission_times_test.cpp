// The time metrics of a run (run/mission_times.hpp) against times worked out by hand, and on a
// whole run through Scenario::run.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "run/mission_times.hpp"
#include "run/run_record.hpp"
#include "run/scenario.hpp"

namespace plumekit::run {
namespace {

// The distance from p to the nearest point of `path`.
double distance_to_path(const std::vector<Vec2>& path, Vec2 p) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t k = 1; k < path.size(); ++k)
    best = std::min(best, distance_to_segment(p, path[k - 1], path[k]));
  return best;
}

// A robot that stood at (0, 0) from 0 to 5 s, then drove to (10, 0) at 0.5 m/s (20 s), arriving
// at `arrived` (later than 25 s when it was kept waiting before it left), and sampled 5 s there.
std::vector<Step> straight_run(double arrived) {
  Step first;
  first.position = {0.0, 0.0};
  first.arrived_s = 0.0;
  first.time_s = 5.0;
  Step second;
  second.position = {10.0, 0.0};
  second.path_in = {{0.0, 0.0}, {10.0, 0.0}};
  second.arrived_s = arrived;
  second.time_s = arrived + 5.0;
  return {first, second};
}

TEST(MissionTimes, TheFirstApproachIsWhereThePathEntersTheDiscAtTheRobotsSpeed) {
  // 1 m about (6, 0.6): the path enters it at x = 6 - sqrt(1 - 0.36) = 5.2, 10.4 s after leaving.
  const std::vector<Step> steps = straight_run(25.0);
  EXPECT_NEAR(first_within(steps, {6.0, 0.6}, 1.0, 0.5), 5.0 + 10.4, 1e-9);
  // It never comes within 0.5 m of it (0.6 m at its closest).
  EXPECT_TRUE(std::isnan(first_within(steps, {6.0, 0.6}, 0.5, 0.5)));
  // A robot kept waiting 10 s before it left drives the same way 10 s later.
  EXPECT_NEAR(first_within(straight_run(35.0), {6.0, 0.6}, 1.0, 0.5), 25.4, 1e-9);
  // Started within the disc: at once. A disc about a point past the path's end: 0.1 m before it.
  EXPECT_EQ(first_within(steps, {0.5, 0.0}, 1.0, 0.5), 0.0);
  EXPECT_NEAR(first_within(steps, {10.9, 0.0}, 1.0, 0.5), 25.0 - 0.1 / 0.5, 1e-9);
}

TEST(MissionTimes, APathOfSeveralLegsCountsTheLegsBeforeTheEntry) {
  std::vector<Step> steps = straight_run(25.0);
  // The second move: up 4 m from (10, 0), then left 4 m, at 0.5 m/s, leaving at 30 s.
  Step third;
  third.position = {6.0, 4.0};
  third.path_in = {{10.0, 0.0}, {10.0, 4.0}, {6.0, 4.0}};
  third.arrived_s = 30.0 + 8.0 / 0.5;
  third.time_s = third.arrived_s + 5.0;
  steps.push_back(third);
  // 0.5 m about (7, 4.3): the second leg (y = 4) enters it at x = 7 + 0.4, 4 + 2.6 m after leaving.
  EXPECT_NEAR(first_within(steps, {7.0, 4.3}, 0.5, 0.5), 30.0 + 6.6 / 0.5, 1e-9);
}

// The drive to the estimate after the last stop (--approach): it leaves when that stop ends.
TEST(MissionTimes, TheApproachAfterTheLastStopCountsFromItsEnd) {
  const std::vector<Step> steps = straight_run(25.0);  // the last stop ends at 30 s at (10, 0)
  const std::vector<Vec2> approach{{10.0, 0.0}, {10.0, 3.0}};
  // 1 m about (10, 3.5): entered 2.5 m up, 5 s after leaving; never without the approach.
  EXPECT_NEAR(first_within(steps, {10.0, 3.5}, 1.0, 0.5, approach), 30.0 + 5.0, 1e-9);
  EXPECT_TRUE(std::isnan(first_within(steps, {10.0, 3.5}, 1.0, 0.5)));
  // Reached before the approach: the approach changes nothing.
  EXPECT_NEAR(first_within(steps, {6.0, 0.6}, 1.0, 0.5, approach), 5.0 + 10.4, 1e-9);
}

TEST(MissionTimes, DetectionIsTheEndOfTheFirstStopAboveTheThreshold) {
  std::vector<Step> steps = straight_run(25.0);
  steps[0].value = 10.0;
  steps[1].value = 80.0;
  EXPECT_EQ(first_detection(steps, 50.0), 30.0);
  EXPECT_EQ(first_detection(steps, 5.0), 5.0);
  EXPECT_TRUE(std::isnan(first_detection(steps, 80.0)));  // above, not at
}

TEST(MissionTimes, GslBenchWantsOneMetreWithinThreeHundredSeconds) {
  MissionTimes t;
  EXPECT_FALSE(t.gsl_bench_success());  // never within 1 m
  t.within_1m_s = 300.0;
  EXPECT_TRUE(t.gsl_bench_success());
  t.within_1m_s = 300.5;
  EXPECT_FALSE(t.gsl_bench_success());
  t.declared_s = 100.0;
  t.ended_s = 120.0;                          // the whole mission, with the drive to the estimate
  EXPECT_TRUE(std::isnan(t.over_optimum()));  // no optimum
  t.optimum_s = 40.0;
  EXPECT_EQ(t.over_optimum(), 3.0);
}

Map block_map() {
  Map m = default_arena(6.0, 3.0);
  m.name = "block";
  m.obstacles = {{{2.5, 1.0}, {3.0, 1.0}, {3.0, 2.0}, {2.5, 2.0}}};
  m.sources = {{4.5, 1.5}};
  return m;
}

TEST(MissionTimes, TheOptimumGoesAroundObstaclesAndARunsTimesFollowItsSteps) {
  const Map map = block_map();
  SteOptions o;
  set_protocol(o, SamplingProtocol::Thesis);  // every stop --stop-s long
  o.model = PlumeModelKind::Physics;
  const Scenario sc(map, o);
  // Straight it is 3.5 m; around the block (0.15 m margin) it is longer than via its corners'
  // margin points and shorter than via points 0.2 m out: (1, 1.5) (2.3, 2.2) (3.2, 2.2) (4.5, 1.5).
  const double around = sc.optimum_path_m({1.0, 1.5}, {4.5, 1.5});
  EXPECT_GT(around, 3.5 + 0.1);
  EXPECT_LT(around, std::hypot(1.3, 0.7) + 0.9 + std::hypot(1.3, 0.7));
  const LocalizationResult r = sc.run({4.5, 1.5}, {1.0, 1.5}, 7);
  const MissionTimes& t = r.times;
  EXPECT_EQ(t.declared_s, r.time_s);
  EXPECT_NEAR(t.optimum_s, around / o.world.speed, 1e-9);
  ASSERT_FALSE(std::isnan(t.within_1m_s)) << "the run never came within 1 m";
  // It comes within 0.5 m no earlier than within 1 m, and within 1 m no earlier than the
  // optimum's way of 1 m less allows.
  EXPECT_GE(t.within_0_5m_s, t.within_1m_s);
  EXPECT_GE(t.within_1m_s, (around - 1.0) / o.world.speed - 1e-9);
  EXPECT_LE(t.within_1m_s, r.time_s);
  // The stops' arrivals: each a sample's length before its end.
  for (const Step& s : r.steps)
    EXPECT_NEAR(s.time_s - s.arrived_s, o.world.sample_s, 1e-6);
}

TEST(MissionTimes, ARobotThatReadsWhileMovingRecordsEachReadingOnItsPathInTime) {
  const Map map = block_map();
  SteOptions o;  // the default protocol reads while moving
  o.model = PlumeModelKind::Physics;
  o.world.sensor = world::gas_sensor_preset("mox-fast");
  const Scenario sc(map, o);
  const LocalizationResult r = sc.run({4.5, 1.5}, {1.0, 1.5}, 7);
  ASSERT_GT(r.steps.size(), 2u);
  std::size_t readings = 0;
  for (std::size_t k = 1; k < r.steps.size(); ++k) {
    const Step &before = r.steps[k - 1], &s = r.steps[k];
    double length = 0.0;
    for (std::size_t i = 1; i < s.path_in.size(); ++i)
      length += norm(s.path_in[i] - s.path_in[i - 1]);
    // One reading per whole reading interval of the drive, each between the stops, on the path.
    EXPECT_EQ(s.on_the_way.size(),
              static_cast<std::size_t>(std::floor(length / o.world.speed * o.world.sample_rate)))
        << k;
    for (const PassingRecord& p : s.on_the_way) {
      EXPECT_GT(p.time_s, before.time_s);
      EXPECT_LE(p.time_s, s.arrived_s + 1e-9);
      EXPECT_LT(distance_to_path(s.path_in, p.position), 1e-6);
      EXPECT_EQ(p.recorded, p.position);  // no position noise here
      EXPECT_GE(p.value, 0.0);
    }
    readings += s.on_the_way.size();
  }
  EXPECT_GT(readings, 10u);
  // The first detection counts a reading on the way: no later than the first stop above it.
  const double threshold = o.method.tracking.detection_threshold;
  for (const Step& s : r.steps)
    if (s.value > threshold) {
      EXPECT_LE(r.times.first_detection_s, s.time_s);
      break;
    }
}

// A run with --approach: after it stops the robot drives to its estimate; the declaration is the
// last stop's end, the mission ends on arrival, and the drive is in the distance.
TEST(MissionTimes, ARobotThatApproachesItsEstimateEndsThere) {
  const Map map = block_map();
  SteOptions o;
  o.model = PlumeModelKind::Physics;
  o.stop.max_samples = 3;  // stopped early, far from its estimate
  o.approach = false;
  const Scenario sc(map, o);
  const LocalizationResult plain = sc.run({4.5, 1.5}, {1.0, 1.5}, 7);
  o.approach = true;
  const LocalizationResult r = Scenario(map, o).run({4.5, 1.5}, {1.0, 1.5}, 7);
  EXPECT_TRUE(plain.approach.empty());
  EXPECT_EQ(plain.approach_s, 0.0);
  ASSERT_GE(r.approach.size(), 2u);
  EXPECT_EQ(r.estimate, plain.estimate);  // the same stops and decisions
  EXPECT_EQ(r.samples, plain.samples);
  EXPECT_LT(norm(r.approach.back() - r.estimate), 0.2);  // there, or at the margin's edge
  EXPECT_NEAR(r.approach.front().x, r.steps.back().position.x, 1e-9);
  // The world moves the robot in whole reading intervals (0.1 s).
  EXPECT_NEAR(r.approach_s, (r.distance_m - plain.distance_m) / o.world.speed, 0.1);
  EXPECT_NEAR(r.times.declared_s, plain.time_s, 1e-9);
  EXPECT_NEAR(r.times.ended_s, r.time_s, 1e-9);
  EXPECT_NEAR(r.time_s, plain.time_s + r.approach_s, 1e-9);
}

}  // namespace
}  // namespace plumekit::run
