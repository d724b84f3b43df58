// Any localization method run against the simulated world (run/method_run.hpp): goals moved off
// obstacles, the trackers' source box, and every method through Scenario::run.
#include <gtest/gtest.h>

#include "core/error.hpp"
#include "map/map.hpp"
#include "run/method_run.hpp"
#include "run/scenario.hpp"

namespace plumekit::ste {
namespace {

Map block_map() {
  Map m = default_arena(6.0, 3.0);
  m.name = "block";
  m.obstacles = {{{2.5, 1.0}, {3.0, 1.0}, {3.0, 2.0}, {2.5, 2.0}}};
  return m;
}

// Asks for the same goals in turn, then stops: what the runner does with each.
class ScriptedMethod : public methods::LocalizationMethod {
 public:
  explicit ScriptedMethod(std::vector<Vec2> goals) : goals_(std::move(goals)) {}
  std::string name() const override { return "scripted"; }
  void observe(const methods::Observation& o) override { seen.push_back(o); }
  methods::Move next(Vec2) override { return {goals_.at(seen.size() - 1), {}, 0.0}; }
  std::optional<Vec2> estimate() const override { return std::nullopt; }
  std::string stopped_by() const override {
    return seen.size() > goals_.size() ? "max_samples" : "";
  }
  std::vector<methods::Observation> seen;

 private:
  std::vector<Vec2> goals_;
};

TEST(MethodRun, GoalsInObstaclesOrOutsideAreMovedToTheNearestFreePoint) {
  const Map map = block_map();
  run::SteOptions o;
  o.method.name = "surge-cast";  // no plume model: the scenario builds none
  const run::Scenario sc(map, o);
  EXPECT_FALSE(sc.has_model());
  world::SimulatedWorld world(map, sc.wind(), {4.5, 0.5}, o.world, 3);
  // Inside the block, beyond the right wall, and a reachable free point.
  ScriptedMethod method({{2.75, 1.5}, {7.0, 1.5}, {1.0, 2.5}});
  run::MethodRunOptions ro;
  ro.space = &sc.free_space();
  const run::LocalizationResult r = run::run_method({1.0, 0.5}, method, world, sc.planner(), ro);
  ASSERT_EQ(r.steps.size(), 4u);
  EXPECT_EQ(r.stopped_by, "max_samples");
  for (const run::Step& s : r.steps)
    EXPECT_TRUE(sc.free_space().contains(s.position));
  // Moved to the block's edge at the margin, and to the right wall's margin.
  EXPECT_NEAR(norm(r.steps[1].position - Vec2{2.75, 1.5}), 0.25 + o.margin, 0.01);
  EXPECT_NEAR(r.steps[2].position.x, map.width - o.margin, 0.01);
  EXPECT_NEAR(r.steps[3].position.x, 1.0, 1e-9);
  // The method saw each stop's reading at the stop (no position noise here).
  ASSERT_EQ(method.seen.size(), 4u);
  EXPECT_EQ(method.seen[2].position, r.steps[2].position);
  EXPECT_EQ(method.seen[2].gas, r.steps[2].value);
  // Without an estimate of its own, a method's estimate is where it ended.
  EXPECT_EQ(r.estimate, r.steps.back().position);
  EXPECT_TRUE(r.posterior.marginal.values.empty());
}

TEST(MethodRun, TheSourceBoxLiesDownwindOfTheSource) {
  run::SourceBox box;
  box.source = {2.0, 4.0};
  box.downwind = {1.0, 0.0};
  EXPECT_TRUE(box.contains({2.0, 4.0}));
  EXPECT_TRUE(box.contains({3.5, 4.99}));
  EXPECT_FALSE(box.contains({3.6, 4.0}));  // past 1.5 m downwind
  EXPECT_FALSE(box.contains({1.9, 4.0}));  // upwind of the source
  EXPECT_FALSE(box.contains({2.5, 5.1}));  // more than 1 m across
  box.downwind = {0.0, -1.0};              // a wind blowing down
  EXPECT_TRUE(box.contains({2.9, 2.6}));
  EXPECT_FALSE(box.contains({2.0, 4.5}));
}

// Lévy taxis' success disc (seed 004 ch. 15): a move through it ends the run where it enters.
TEST(MethodRun, AMoveThroughTheSourceDiscEndsTheRunWhereItEnters) {
  const Map map = block_map();
  run::SteOptions o;
  o.method.name = "levy-taxis";
  const run::Scenario sc(map, o);
  world::SimulatedWorld world(map, sc.wind(), {4.5, 2.0}, o.world, 3);
  ScriptedMethod method({{5.5, 2.0}, {5.5, 2.5}});  // straight through the source
  run::MethodRunOptions ro;
  ro.space = &sc.free_space();
  ro.disc = run::SourceDisc{{4.5, 2.0}, 0.5};
  const run::LocalizationResult r = run::run_method({3.5, 2.0}, method, world, sc.planner(), ro);
  EXPECT_EQ(r.stopped_by, "reached");
  EXPECT_TRUE(r.reached);
  ASSERT_EQ(r.steps.size(), 2u);
  EXPECT_NEAR(r.steps[1].position.x, 4.0, 1e-9);
  EXPECT_NEAR(r.steps[1].position.y, 2.0, 1e-9);
  EXPECT_NEAR(r.distance_m, 0.5, 1e-9);
  EXPECT_TRUE(ro.disc->contains({4.9, 2.2}));
  EXPECT_FALSE(ro.disc->contains({5.1, 2.0}));
}

TEST(MethodRun, EveryMethodRunsOnAMapWithAnObstacleAndRepeatsItself) {
  const Map map = block_map();
  for (const std::string& name : run::method_names()) {
    if (name == "ste") continue;
    run::SteOptions o;
    o.method.name = run::find_method(name).name;
    o.method.max_steps = 40;
    const run::Scenario sc(map, o);
    const run::LocalizationResult a = sc.run({4.5, 0.5}, {1.0, 2.5}, 7);
    const run::LocalizationResult b = sc.run({4.5, 0.5}, {1.0, 2.5}, 7);
    EXPECT_EQ(a.method, name);
    EXPECT_GE(a.samples, 1) << name;
    EXPECT_LE(a.samples, 40) << name;
    EXPECT_FALSE(a.stopped_by.empty()) << name;
    EXPECT_EQ(a.reached, a.stopped_by == "reached") << name;
    for (const run::Step& s : a.steps)
      EXPECT_TRUE(sc.free_space().contains(s.position)) << name;
    // The same seed gives the same run.
    ASSERT_EQ(a.steps.size(), b.steps.size()) << name;
    EXPECT_EQ(a.estimate, b.estimate) << name;
  }
}

TEST(MethodRun, UnknownMethodNamesTheFieldAndTheChoices) {
  try {
    run::find_method("infotaxis");
    FAIL();
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "ste.method");
    EXPECT_NE(std::string(e.what()).find("surge-cast"), std::string::npos);
  }
}

}  // namespace
}  // namespace plumekit::ste

namespace plumekit::ste {
namespace {

// The loop's order, whatever a phase costs: a stop read in three parts, a move in two, the run
// ended by the second decision. run_loop() does the phases in turn; act() one action at a time.
struct PhasedRobot {
  std::string log;
  int readings = 0, legs = 0, decisions = 0;
  bool sense() {
    log += "s";
    return ++readings % 3 == 0;
  }
  bool decide() {
    log += "D";
    return ++decisions == 2;
  }
  bool move() {
    log += "m";
    return ++legs % 2 == 0;
  }
};

TEST(RunLoop, SensesDecidesAndMovesInTurnUntilADecisionEndsTheRun) {
  PhasedRobot alone;
  run::run_loop(alone);
  EXPECT_EQ(alone.log, "sssDmmsssD");
  // One action at a time, as a team's robots are stepped.
  PhasedRobot stepped;
  run::Phase phase = run::Phase::Sense;
  std::vector<run::Phase> phases;
  while (phase != run::Phase::Done) {
    phase = run::act(stepped, phase);
    phases.push_back(phase);
  }
  EXPECT_EQ(stepped.log, alone.log);
  EXPECT_EQ(phases.size(), alone.log.size());
  EXPECT_EQ(phases[2], run::Phase::Decide);
  EXPECT_EQ(phases[3], run::Phase::Move);
  EXPECT_EQ(run::act(stepped, run::Phase::Done), run::Phase::Done);
  EXPECT_EQ(stepped.log, alone.log);  // a robot done does nothing
}

// The runner's stop rules, after the method's own: the box or the disc ("reached"), then the
// stop budget.
TEST(RunLoop, AMethodsOwnReasonComesBeforeTheRunnersRules) {
  ScriptedMethod going({{1.0, 1.0}});
  run::MethodRunOptions o;
  o.max_stops = 5;
  EXPECT_EQ(run::stop_reason(going, {0.0, 0.0}, 4, o), "");
  EXPECT_EQ(run::stop_reason(going, {0.0, 0.0}, 5, o), "max_samples");
  o.disc = run::SourceDisc{{0.0, 0.2}, 0.5};
  EXPECT_EQ(run::stop_reason(going, {0.0, 0.0}, 5, o), "reached");
  o.disc.reset();
  o.box = run::SourceBox{{-0.5, 0.0}};
  EXPECT_EQ(run::stop_reason(going, {0.0, 0.0}, 1, o), "reached");
  ScriptedMethod done({});
  done.observe({});  // one observation more than its goals: it stops by its own rule
  EXPECT_EQ(run::stop_reason(done, {0.0, 0.0}, 1, o), "max_samples");
  o.box.reset();
  EXPECT_EQ(run::stop_reason(done, {0.0, 0.0}, 1, o), "max_samples");
}

}  // namespace
}  // namespace plumekit::ste
