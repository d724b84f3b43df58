// STE in the local framework (seed 004 ch. 12, Algorithm 1; methods/local_framework.hpp): the
// sample budget, how the local map moves, an obstacle's zero, odometry, and a whole run without a
// map.
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.hpp"
#include "map/map.hpp"
#include "methods/local_framework.hpp"
#include "run/method_run.hpp"
#include "run/scenario.hpp"

namespace plumekit::ste {
namespace {

TEST(LocalFramework, BudgetFallsByOneWithoutInformationAndByTheEntropyRatioWithIt) {
  EXPECT_DOUBLE_EQ(methods::next_budget(7.0, 2.0, 2.0), 6.0);  // entropy unchanged: 1
  EXPECT_DOUBLE_EQ(methods::next_budget(7.0, 2.5, 2.0), 6.0);  // entropy up: 1
  EXPECT_DOUBLE_EQ(methods::next_budget(7.0, 1.0, 2.0), 6.5);  // halved: 0.5
  EXPECT_DOUBLE_EQ(methods::next_budget(0.3, 0.2, 2.0), 0.2);  // a tenth: 0.1
}

methods::Observation stop_at(Vec2 p, double gas, Vec2 wind = {1.0, 0.0}) {
  methods::Observation o;
  o.position = p;
  o.gas = gas;
  o.wind = wind;
  return o;
}

TEST(LocalFramework, AMapWhereNothingWasSensedMovesCrosswindByItsSize) {
  methods::LocalFrameworkSte m({}, 3);
  const Vec2 at{5.0, 2.0};
  const Vec2 wind{0.0, 0.8};  // blowing up: crosswind is along x
  methods::Move move;
  int stops = 0;
  do {
    m.observe(stop_at(at, 0.0, wind));
    ASSERT_EQ(m.stopped_by(), "");
    move = m.next(at);
    ++stops;
  } while (norm(move.goal - at) < 1.9 && stops < 40);
  EXPECT_TRUE(move.straight);
  EXPECT_NEAR(std::abs(move.goal.x - at.x), 2.0, 1e-9);  // one map size, crosswind
  EXPECT_NEAR(move.goal.y, at.y, 1e-9);
  // Each of the 7 samples' zero taught little: the budget took at least 7 samples.
  EXPECT_GE(stops, 7);
  EXPECT_LE(m.budget(), 0.0);
  // The next stop opens a new map there, with a fresh budget and no sample of the last.
  m.observe(stop_at(move.goal, 0.0, wind));
  EXPECT_EQ(m.maps(), 2);
  EXPECT_EQ(m.map_samples(), 1);
  EXPECT_DOUBLE_EQ(m.budget(), 6.0);
}

TEST(LocalFramework, AMapWithGasMovesOntoItsMostProbableSource) {
  methods::LocalFrameworkOptions o;
  o.budget = 3.0;
  methods::LocalFrameworkSte m(o, 5);
  // Readings that rise upwind (wind along +x): the source lies upwind, at the map's edge.
  const Vec2 stops[] = {{5.5, 2.0}, {5.0, 2.0}, {4.5, 2.0}, {5.0, 2.3}, {5.0, 1.7}, {4.4, 2.0}};
  const double gas[] = {80.0, 120.0, 200.0, 60.0, 60.0, 220.0};
  methods::Move move;
  for (int k = 0; k < 6; ++k) {
    m.observe(stop_at(stops[k], gas[k]));
    move = m.next(stops[k]);
    if (m.budget() <= 0.0) {
      // The MAP of a map opened at (5.5, 2): inside it, upwind of its centre.
      EXPECT_LT(move.goal.x, 5.5);
      EXPECT_GE(move.goal.x, 4.5 - 1e-9);
      EXPECT_NEAR(move.goal.y, 2.0, 1.0);
      return;
    }
  }
  FAIL() << "the budget of 3 was never spent";
}

TEST(LocalFramework, AnObstaclesZeroGoesToTheGoalAndCosts) {
  methods::LocalFrameworkSte m({}, 7);
  m.observe(stop_at({5.0, 2.0}, 0.0));
  const methods::Move move = m.next({5.0, 2.0});
  const double before = m.budget();
  methods::Observation blocked = stop_at({5.1, 2.0}, 900.0);  // its reading is not used
  blocked.blocked = true;
  m.observe(blocked);
  EXPECT_EQ(m.map_samples(), 2);
  EXPECT_LT(m.budget(), before);
  EXPECT_TRUE(move.straight);
}

TEST(LocalFramework, BadOptionsNameTheirField) {
  methods::LocalFrameworkOptions o;
  o.budget = 0.0;
  try {
    methods::LocalFrameworkSte m(o, 1);
    FAIL();
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "local.budget");
  }
}

// A straight move stops before an obstacle, and the next observation says so.
class StraightAhead : public methods::LocalizationMethod {
 public:
  std::string name() const override { return "straight"; }
  void observe(const methods::Observation& o) override { seen.push_back(o); }
  methods::Move next(Vec2) override {
    methods::Move m;
    m.goal = {5.0, 1.5};  // through the block
    m.straight = true;
    return m;
  }
  std::optional<Vec2> estimate() const override { return std::nullopt; }
  std::string stopped_by() const override { return seen.size() >= 2 ? "max_samples" : ""; }
  std::vector<methods::Observation> seen;
};

TEST(LocalFramework, AStraightMoveStopsAtTheFirstObstacle) {
  Map map = default_arena(6.0, 3.0);
  map.obstacles = {{{2.5, 1.0}, {3.0, 1.0}, {3.0, 2.0}, {2.5, 2.0}}};
  run::SteOptions o;
  o.method.name = "ste-local";
  const run::Scenario sc(map, o);
  world::SimulatedWorld world(map, sc.wind(), {0.5, 0.5}, o.world, 3);
  StraightAhead method;
  run::MethodRunOptions ro;
  ro.space = &sc.free_space();
  const run::LocalizationResult r = run::run_method({1.0, 1.5}, method, world, sc.planner(), ro);
  ASSERT_EQ(method.seen.size(), 2u);
  EXPECT_FALSE(method.seen[0].blocked);
  EXPECT_TRUE(method.seen[1].blocked);
  // Stopped at the block's margin, on the straight line.
  EXPECT_NEAR(r.steps[1].position.x, 2.5 - o.margin, 0.02);
  EXPECT_NEAR(r.steps[1].position.y, 1.5, 1e-9);
}

TEST(LocalFramework, OdometryDriftsWithDistanceAndNotWithout) {
  const Map map = default_arena();
  run::SteOptions o;
  o.method.name = "ste-local";
  const run::Scenario sc(map, o);
  world::WorldOptions w = o.world;
  w.filament.min_spinup = 2.0;
  w.filament.max_spinup = 4.0;
  w.odometry_drift = 0.05;
  world::SimulatedWorld world(map, sc.wind(), {1.0, 2.0}, w, 9);
  EXPECT_EQ(world.stop({8.0, 2.0}).position, (Vec2{8.0, 2.0}));  // not moved yet
  double drift = 0.0;
  Vec2 p{8.0, 2.0};
  for (int k = 0; k < 20; ++k) {
    const Vec2 q{p.x - 0.3, 2.0};
    world.travel({p, q}, 0.3);
    p = q;
    drift = norm(world.stop(p).position - p);
  }
  // 6 m travelled: the drift's std per axis is 0.05 sqrt(6) = 0.12 m.
  EXPECT_GT(drift, 0.0);
  EXPECT_LT(drift, 0.6);
}

TEST(LocalFramework, ARunWithoutAMapFindsTheSourceAndRepeatsItself) {
  run::SteOptions o;
  o.method.name = "ste-local";
  world::set_world(o.world.filament, "thesis");
  o.world.filament.min_spinup = 5.0;
  o.world.filament.max_spinup = 20.0;
  o.world.odometry_drift = 0.02;
  const Map map = default_arena();
  const run::Scenario sc(map, o);
  EXPECT_FALSE(sc.has_model());  // no global plume model: it knows no map
  const run::LocalizationResult a = sc.run({2.0, 2.0}, {6.0, 2.2}, 4);
  const run::LocalizationResult b = sc.run({2.0, 2.0}, {6.0, 2.2}, 4);
  EXPECT_EQ(a.method, "ste-local");
  EXPECT_EQ(a.stopped_by, "entropy");
  EXPECT_LT(norm(a.estimate - Vec2{2.0, 2.0}), 1.0);
  EXPECT_EQ(a.estimate, b.estimate);
  EXPECT_EQ(a.samples, b.samples);
  // Odometry: what the robot recorded is not where it was.
  EXPECT_NE(a.steps.back().recorded, a.steps.back().position);
}

}  // namespace
}  // namespace plumekit::ste
