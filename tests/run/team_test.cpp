// Robot teams (seed 004 ch. 13; run/team.hpp): the rules on hand-made cases, a team of one is the
// robot alone, shared samples reach a teammate, robots keep their separation.
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.hpp"
#include "run/scenario.hpp"
#include "run/team.hpp"
#include "ste/grid_estimator.hpp"
#include "ste/mission.hpp"

namespace plumekit::ste {
namespace {

// The thesis's open arena (10 x 4 m, the default inlet), the physics model in the thesis's
// world, and a short spin-up for a test.
run::SteOptions team_options(int robots, run::TeamStrategy strategy) {
  run::SteOptions o;
  o.model = run::PlumeModelKind::Physics;
  world::set_world(o.world.filament, "thesis");
  o.world.filament.min_spinup = 5.0;
  o.world.filament.max_spinup = 20.0;
  o.stop.max_samples = 25;
  o.team.robots = robots;
  o.team.strategy = strategy;
  return o;
}

const Vec2 kSource{1.5, 2.0};
const Vec2 kStart{8.0, 2.2};

TEST(Team, SeparationRuleLetsRobotsPartButNotClose) {
  const Vec2 other{1.0, 0.0};
  EXPECT_TRUE(run::may_move({-1.0, 0.0}, {0.0, 0.0}, other, 0.5));  // ends 1 m away
  EXPECT_FALSE(run::may_move({0.0, 0.0}, {0.6, 0.0}, other, 0.5));  // ends 0.4 m away, closer
  EXPECT_TRUE(run::may_move({0.9, 0.0}, {0.8, 0.0}, other, 0.5));   // too close, but moving away
  EXPECT_TRUE(run::may_move({0.6, 0.3}, {0.6, -0.3}, other, 0.5));  // 0.5 m before and after
  EXPECT_TRUE(run::may_move({0.0, 0.0}, {0.5, 0.0}, other, 0.45));  // keeps a smaller separation
}

TEST(Team, AGoalWhereATeammateIsMovesToTheNearestFreePoint) {
  const auto anywhere = [](Vec2) { return true; };
  // Clear of every teammate: kept.
  EXPECT_EQ(*run::free_goal({1.0, 1.0}, {{2.0, 1.0}, {1.0, 2.0}}, 0.3, anywhere), (Vec2{1.0, 1.0}));
  // A teammate 0.1 m off: the first point of the nearest ring clear of it, 0.3 m away.
  const Vec2 moved = *run::free_goal({1.0, 1.0}, {{1.1, 1.0}}, 0.3, anywhere);
  EXPECT_GE(norm(moved - Vec2{1.1, 1.0}), 0.3);
  EXPECT_NEAR(norm(moved - Vec2{1.0, 1.0}), 0.3, 1e-12);
  // Only points the caller accepts (free space, the robot's piece of it): here y <= 1.
  const Vec2 below =
      *run::free_goal({1.0, 1.0}, {{1.0, 1.0}}, 0.3, [](Vec2 g) { return g.y <= 1.0; });
  EXPECT_LE(below.y, 1.0);
  EXPECT_GE(norm(below - Vec2{1.0, 1.0}), 0.3);
  // Nowhere usable: none.
  EXPECT_FALSE(run::free_goal({1.0, 1.0}, {{1.0, 1.0}}, 0.3, [](Vec2) { return false; }));
}

TEST(Team, TaskSwapTakesTheTeammatesGoalWhenThatShortensTheTeamsPath) {
  const auto straight = [](Vec2 a, Vec2 b) { return norm(a - b); };
  // Robot at the origin chose a goal 10 m east; a teammate 9 m east heads for 1 m east. Swapped,
  // each goes 1 m instead of 10 and 8: the team saves 16 m.
  const run::Heading robot{{0.0, 0.0}, {10.0, 0.0}};
  std::vector<run::Heading> moving{{{9.0, 0.0}, {1.0, 0.0}}};
  EXPECT_EQ(run::best_swap(robot, moving, straight), 0);
  // Of two teammates, the one whose swap saves more: the second saves 18 m.
  moving = {{{5.0, 3.0}, {5.0, 2.0}}, {{10.0, 0.5}, {0.0, 0.5}}};
  EXPECT_EQ(run::best_swap(robot, moving, straight), 1);
  // No swap saves anything: teammates already bound for the nearer goals.
  moving = {{{9.0, 0.0}, {9.5, 0.0}}, {{0.0, 3.0}, {0.0, 4.0}}};
  EXPECT_EQ(run::best_swap(robot, moving, straight), -1);
  // An unreachable swapped goal (infinite distance) is never taken.
  const auto walled = [](Vec2 a, Vec2 b) {
    return b.x > 5.0 && a.x < 5.0 ? std::numeric_limits<double>::infinity() : norm(a - b);
  };
  EXPECT_EQ(run::best_swap({{0.0, 0.0}, {1.0, 0.0}}, {{{9.0, 0.0}, {8.0, 0.0}}}, walled), -1);
}

TEST(Team, StrategiesParseAndBadOptionsNameTheirField) {
  EXPECT_EQ(run::parse_team_strategy("collaborative"), run::TeamStrategy::Collaborative);
  EXPECT_STREQ(to_string(run::TeamStrategy::Cooperative), "cooperative");
  try {
    run::parse_team_strategy("swarm");
    FAIL();
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "ste.team.strategy");
  }
  run::SteOptions o = team_options(0, run::TeamStrategy::Individualist);
  try {
    o.validate();
    FAIL();
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "ste.team.robots");
  }
  o = team_options(2, run::TeamStrategy::Individualist);
  o.method.name = "surge-cast";  // teams run STE
  try {
    o.validate();
    FAIL();
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "ste.team.robots");
  }
}

TEST(Team, MissionCountsItsOwnSamplesAgainstItsBudget) {
  const Map map = default_arena();
  run::SteOptions o = team_options(1, run::TeamStrategy::Cooperative);
  o.stop.max_samples = 3;
  o.stop.entropy_fraction = 0.0;  // only the budget stops it
  const run::Scenario sc(map, o);
  const auto est = sc.make_estimator(1);
  Mission m(*est, sc.planner(), sc.navigator(), sc.options().stop);
  m.add({8.0, 2.0}, 0.0, {{{7.0, 1.0}, 0.0}, {{7.0, 3.0}, 0.0}, {{6.0, 2.0}, 0.0}});
  m.add({7.5, 2.0}, 0.0, {{{5.0, 2.0}, 0.0}});
  EXPECT_EQ(m.samples(), 6);
  EXPECT_EQ(m.own_samples(), 2);
  EXPECT_FALSE(m.stopped());
  m.add({7.0, 2.0}, 0.0);
  EXPECT_EQ(m.stopped_by(), "max_samples");
  // A shared sample that is not finite is refused before anything is added.
  Mission n(*sc.make_estimator(1), sc.planner(), sc.navigator(), sc.options().stop);
  EXPECT_THROW(n.add({8.0, 2.0}, 0.0, {{{NAN, 1.0}, 0.0}}), InputError);
}

TEST(Team, VirtualSamplesAtTeammatesGoalsChangeWhereARobotGoes) {
  const Map map = default_arena();
  const run::Scenario sc(map, team_options(1, run::TeamStrategy::Collaborative));
  const auto est = sc.make_estimator(1);
  Mission m(*est, sc.planner(), sc.navigator(), sc.options().stop);
  m.add({6.0, 2.0}, 40.0);
  m.add({6.0, 2.5}, 15.0);
  const Vec2 robot{6.0, 2.5};
  const Posterior before = m.posterior();
  const Vec2 alone = m.next(robot).goal;
  // A teammate about to sample there: that information is as good as taken.
  const Vec2 beside = m.next(robot, {alone}).goal;
  EXPECT_GT(norm(beside - alone), 0.1);
  // The mission's own posterior is untouched.
  EXPECT_EQ(m.samples(), 2);
  EXPECT_EQ(m.posterior().entropy, before.entropy);
  EXPECT_EQ(m.next(robot).goal, alone);
}

TEST(Team, ATeamOfOneIsTheRobotAlone) {
  const Map map = default_arena();
  // The fast MOX sensor reads on the way too.
  for (const std::string sensor : {"ideal", "mox-fast"}) {
    SCOPED_TRACE(sensor);
    run::SteOptions o = team_options(1, run::TeamStrategy::Individualist);
    o.world.sensor = world::gas_sensor_preset(sensor);
    o.approach = false;  // a team does not drive to its estimate; a robot alone would
    const run::Scenario sc(map, o);
    const run::LocalizationResult alone = sc.run(kSource, kStart, 11);
    const run::LocalizationResult team = sc.run_team(kSource, {kStart}, 11);
    ASSERT_EQ(team.team.size(), 1u);
    ASSERT_EQ(alone.steps.size(), team.steps.size());
    for (std::size_t k = 0; k < alone.steps.size(); ++k) {
      EXPECT_EQ(alone.steps[k].position, team.steps[k].position) << k;
      EXPECT_EQ(alone.steps[k].value, team.steps[k].value) << k;
      EXPECT_EQ(alone.steps[k].time_s, team.steps[k].time_s) << k;
      EXPECT_EQ(alone.steps[k].distance_m, team.steps[k].distance_m) << k;
      EXPECT_EQ(alone.steps[k].entropy, team.steps[k].entropy) << k;
      EXPECT_EQ(alone.steps[k].path_in, team.steps[k].path_in) << k;
    }
    EXPECT_EQ(alone.estimate, team.estimate);
    EXPECT_EQ(alone.samples, team.samples);
    EXPECT_EQ(alone.distance_m, team.distance_m);
    EXPECT_EQ(alone.time_s, team.time_s);
    EXPECT_EQ(alone.stopped_by, team.stopped_by);
    EXPECT_EQ(team.declared_by, 0);
  }
}

// The entropy a fresh estimator reaches from these samples, in this order.
double entropy_after(const run::Scenario& sc, const std::vector<run::Step>& samples) {
  const auto est = sc.make_estimator(1);
  for (const run::Step& s : samples)
    est->add(s.recorded, s.value);
  return est->posterior().entropy;
}

TEST(Team, CooperativeRobotsShareEverySampleAndIndividualistsNone) {
  const Map map = default_arena();
  for (run::TeamStrategy strategy :
       {run::TeamStrategy::Cooperative, run::TeamStrategy::Individualist}) {
    const run::Scenario sc(map, team_options(2, strategy));
    const run::LocalizationResult r = sc.run(kSource, kStart, 5);
    ASSERT_EQ(r.team.size(), 2u);
    const std::vector<run::Step>& first = r.team[0].steps;
    const std::vector<run::Step>& second = r.team[1].steps;
    ASSERT_GE(first.size(), 1u);
    ASSERT_GE(second.size(), 1u);
    // Both stops end at the same time; robot 1 decides first, so robot 2's first posterior holds
    // robot 1's sample too when they cooperate.
    EXPECT_EQ(first[0].time_s, second[0].time_s);
    EXPECT_EQ(first[0].entropy, entropy_after(sc, {first[0]}));
    if (strategy == run::TeamStrategy::Cooperative)
      EXPECT_EQ(second[0].entropy, entropy_after(sc, {first[0], second[0]}));
    else
      EXPECT_EQ(second[0].entropy, entropy_after(sc, {second[0]}));
    EXPECT_EQ(r.samples, static_cast<int>(first.size() + second.size()));
    EXPECT_DOUBLE_EQ(r.distance_m, r.team[0].distance_m + r.team[1].distance_m);
  }
}

TEST(Team, RobotsKeepTheirSeparationAndRepeatThemselves) {
  const Map map = default_arena();
  for (run::TeamStrategy strategy :
       {run::TeamStrategy::Individualist, run::TeamStrategy::Cooperative,
        run::TeamStrategy::Collaborative}) {
    run::SteOptions o = team_options(3, strategy);
    // One team's sensor reads on the way: every robot's reads interleave on the one thread.
    if (strategy == run::TeamStrategy::Collaborative)
      o.world.sensor = world::gas_sensor_preset("mox-fast");
    const run::Scenario sc(map, o);
    const std::vector<Vec2> starts = sc.team_starts(kStart, kSource);
    ASSERT_EQ(starts.size(), 3u);
    const run::LocalizationResult a = sc.run(kSource, kStart, 9);
    const run::LocalizationResult b = sc.run(kSource, kStart, 9);
    ASSERT_EQ(a.team.size(), 3u);
    for (std::size_t k = 0; k < 3; ++k) {
      EXPECT_EQ(a.team[k].start, starts[k]);
      EXPECT_GE(a.team[k].closest_m, sc.options().team.separation - 1e-9) << to_string(strategy);
      for (const run::Step& s : a.team[k].steps)
        EXPECT_TRUE(sc.free_space().contains(s.position));
      // The same seed gives the same run.
      ASSERT_EQ(a.team[k].steps.size(), b.team[k].steps.size());
      for (std::size_t i = 0; i < a.team[k].steps.size(); ++i)
        EXPECT_EQ(a.team[k].steps[i].value, b.team[k].steps[i].value);
    }
    EXPECT_EQ(a.estimate, b.estimate);
    EXPECT_LT(norm(a.estimate - kSource), 1.0) << to_string(strategy);
    // The mission ends at the declaration: no robot's stop ends after it.
    if (a.stopped_by == "entropy") {
      for (const run::TeamRobot& t : a.team)
        EXPECT_LE(t.steps.back().time_s, a.time_s);
    }
  }
}

// Robots that give up their goals at once, with a sensor that reads on the way: every wait, side
// step and give-up keeps the one thread's plume clock (SharedPlume::promise throws otherwise).
TEST(Team, ImpatientRobotsWithAMemorySensorKeepTheWorldClock) {
  const Map map = default_arena();
  for (run::TeamStrategy strategy :
       {run::TeamStrategy::Individualist, run::TeamStrategy::Collaborative}) {
    run::SteOptions o = team_options(3, strategy);
    o.world.sensor = world::gas_sensor_preset("mox-fast");
    o.team.patience_s = 0.2;
    o.team.separation = 0.6;
    const run::Scenario sc(map, o);
    const run::LocalizationResult r = sc.run(kSource, kStart, 13);
    ASSERT_EQ(r.team.size(), 3u);
    for (const run::TeamRobot& t : r.team)
      EXPECT_GE(t.closest_m, 0.6 - 1e-9) << to_string(strategy);
  }
}

TEST(Team, StartsSitSideBySideInTheSourcesPieceOfFreeSpace) {
  const Map map = default_arena();
  run::SteOptions o = team_options(4, run::TeamStrategy::Cooperative);
  o.team.separation = 0.6;
  const run::Scenario sc(map, o);
  const std::vector<Vec2> s = sc.team_starts({9.7, 0.3}, kSource);  // a corner
  ASSERT_EQ(s.size(), 4u);
  for (std::size_t i = 0; i < s.size(); ++i) {
    EXPECT_TRUE(sc.free_space().contains(s[i]));
    for (std::size_t j = 0; j < i; ++j)
      EXPECT_GE(norm(s[i] - s[j]), 0.6 - 1e-9);
  }
  o.team.robots = 64;
  o.team.separation = 3.0;  // 64 robots 3 m apart do not fit in 10 x 4 m
  const run::Scenario crowded(map, o);
  EXPECT_THROW(crowded.team_starts(kStart, kSource), InputError);
}

}  // namespace
}  // namespace plumekit::ste
