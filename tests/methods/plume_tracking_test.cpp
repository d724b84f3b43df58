#include "methods/plume_tracking.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "core/error.hpp"
#include "methods/wind_statistics.hpp"

namespace plumekit::methods {
namespace {

// The seeds' wind tunnel: an open 32 x 8 m arena. With the default 0.5 m margin the search area
// is [0.5, 31.5] x [0.5, 7.5], centred on (16, 4).
class PlumeTrackingTest : public ::testing::Test {
 protected:
  Map map = default_arena(32.0, 8.0);
  SearchArea area{&map};
  TrackingOptions options;
};

const Vec2 kWind{1.0, 0.0};  // along +x: upwind is -x, the left of upwind is -y

Observation stop(Vec2 p, double gas, Vec2 wind = kWind) {
  Observation o;
  o.position = p;
  o.gas = gas;
  o.wind = wind;
  return o;
}

// Observes a stop and returns the method's next goal.
Vec2 goal_after(LocalizationMethod& method, Vec2 p, double gas, Vec2 wind = kWind) {
  method.observe(stop(p, gas, wind));
  return method.next(p).goal;
}

void expect_at(Vec2 actual, Vec2 expected, double tol = 1e-9) {
  EXPECT_NEAR(actual.x, expected.x, tol) << to_string(actual) << " vs " << to_string(expected);
  EXPECT_NEAR(actual.y, expected.y, tol) << to_string(actual) << " vs " << to_string(expected);
}

TEST_F(PlumeTrackingTest, SweepStepsCrosswindAndTurnsUpwindAtTheWall) {
  SweepingMethod sweep(area, options);
  // The first sweep direction points to the side with more room: -y from (20, 5).
  Vec2 p{20.0, 5.0};
  for (double y : {4.0, 3.0, 2.0, 1.0}) {
    p = goal_after(sweep, p, 0.0);
    expect_at(p, {20.0, y});
  }
  expect_at(sweep.sweeper().direction(), {0.0, -1.0});
  // (20, 0) would leave the area: one step upwind, sweep direction inverted.
  p = goal_after(sweep, p, 0.0);
  expect_at(p, {19.0, 1.0});
  expect_at(sweep.sweeper().direction(), {0.0, 1.0});
  expect_at(goal_after(sweep, p, 0.0), {19.0, 2.0});
  EXPECT_TRUE(sweep.acquiring());
  // The sweeping method goes on sweeping through a detection.
  expect_at(goal_after(sweep, {19.0, 2.0}, 500.0), {19.0, 3.0});
}

TEST_F(PlumeTrackingTest, SweepStepsTowardTheCentreWhenUpwindLeavesToo) {
  SweepingMethod sweep(area, options);
  Vec2 p{1.0, 2.0};
  expect_at(goal_after(sweep, p, 0.0), {1.0, 3.0});  // +y: toward the centre's side
  // At the upwind wall's corner both the crosswind and the upwind step leave the area.
  Vec2 corner{1.0, 7.2};
  const Vec2 g = goal_after(sweep, corner, 0.0);
  const Vec2 to_centre = Vec2{16.0, 4.0} - corner;
  expect_at(g, corner + (1.0 / norm(to_centre)) * to_centre);
  expect_at(sweep.sweeper().direction(), {0.0, -1.0});  // inverted
}

TEST_F(PlumeTrackingTest, SurgeCastSurgesAndCastsWideningOnAlternatingSides) {
  SurgeCast method(area, options);
  EXPECT_EQ(method.name(), "surge-cast");
  expect_at(goal_after(method, {20.0, 4.0}, 100.0), {19.0, 4.0});  // surge upwind
  EXPECT_FALSE(method.acquiring());
  // Steady wind: the first cast goes to the sweep direction's side (-y on the centre line).
  Vec2 p{19.0, 4.0};
  const Vec2 expected[] = {{19.0, 3.0}, {19.0, 5.0}, {19.0, 2.0}, {19.0, 6.0}, {19.0, 1.0}};
  for (int k = 0; k < 5; ++k) {
    p = goal_after(method, p, 0.0);
    expect_at(p, expected[k]);
    EXPECT_EQ(method.casts(), k + 1);
  }
  // A non-detection after max_casts (5) casts sweeps again: from (19, 1) the sweep (-y) hits the
  // wall, so it steps upwind.
  expect_at(goal_after(method, p, 0.0), {18.0, 1.0});
  EXPECT_TRUE(method.acquiring());
  // A detection while sweeping surges again.
  expect_at(goal_after(method, {18.0, 1.0}, 80.0), {17.0, 1.0});
  EXPECT_FALSE(method.acquiring());
}

TEST_F(PlumeTrackingTest, SurgeCastRestartsItsCastsOnADetection) {
  SurgeCast method(area, options);
  goal_after(method, {20.0, 4.0}, 100.0);
  goal_after(method, {19.0, 4.0}, 0.0);                           // cast 1
  goal_after(method, {19.0, 3.0}, 0.0);                           // cast 2
  expect_at(goal_after(method, {19.0, 5.0}, 60.0), {18.0, 5.0});  // surge
  EXPECT_EQ(method.casts(), 0);
  expect_at(goal_after(method, {18.0, 5.0}, 0.0), {18.0, 4.0});  // one step again
}

TEST_F(PlumeTrackingTest, SurgeCastCastsFirstToWhereTheWindSwungThePlume) {
  SurgeCast method(area, options);
  goal_after(method, {20.0, 4.0}, 100.0);
  // The wind turned 10 degrees counter-clockwise: the plume moved toward +y.
  const double a = radians(10.0);
  const Vec2 g = goal_after(method, {19.0, 4.0}, 0.0, heading(a));
  expect_at(g, {19.0 - std::sin(a), 4.0 + std::cos(a)});
  // Clockwise: toward -y.
  SurgeCast other(area, options);
  goal_after(other, {20.0, 4.0}, 100.0);
  expect_at(goal_after(other, {19.0, 4.0}, 0.0, heading(-a)),
            {19.0 - std::sin(a), 4.0 - std::cos(a)});
}

TEST_F(PlumeTrackingTest, SurgeCastCutsACastAtTheWall) {
  SurgeCast method(area, options);
  goal_after(method, {20.0, 2.0}, 100.0);
  // From (19, 2) the sweep direction points +y (toward the centre); the second cast, 2 m toward
  // -y from (19, 3), ends at the margin.
  expect_at(goal_after(method, {19.0, 2.0}, 0.0), {19.0, 3.0});
  expect_at(goal_after(method, {19.0, 3.0}, 0.0), {19.0, 1.0});
  expect_at(goal_after(method, {19.0, 1.0}, 0.0), {19.0, 4.0});
  expect_at(goal_after(method, {19.0, 1.2}, 0.0), {19.0, 0.5});
}

// Zigzag with alpha = 60: a leg on the left of upwind (side +1) is (-0.5, -0.866).
const double kS60 = std::sin(radians(60.0));

TEST_F(PlumeTrackingTest, ZigzagFlipsOnLossBySeed002) {
  Zigzag method(area, options);
  expect_at(goal_after(method, {20.0, 4.0}, 100.0), {19.5, 4.0 - kS60});
  EXPECT_EQ(method.side(), 1);
  // Still in the plume: no flip.
  expect_at(goal_after(method, {19.5, 4.0 - kS60}, 100.0), {19.0, 4.0 - 2 * kS60});
  // Lost: flip to -alpha.
  expect_at(goal_after(method, {19.0, 3.0}, 10.0), {18.5, 3.0 + kS60});
  EXPECT_EQ(method.side(), -1);
  // Still out: no second flip; the third consecutive non-detection sweeps again.
  expect_at(goal_after(method, {18.5, 4.0}, 10.0), {18.0, 4.0 + kS60});
  EXPECT_FALSE(method.acquiring());
  goal_after(method, {18.0, 5.0}, 10.0);
  EXPECT_TRUE(method.acquiring());
}

TEST_F(PlumeTrackingTest, StepsFromWhereTheRobotStandsNotFromItsNoisyFix) {
  // The stop records (20, 5) while the robot stands at (20.8, 4.3): the zigzag's step (0.5 m
  // upwind, sin 60 to the side) is taken from the robot, one step long whatever the fix's error.
  Zigzag method(area, options);
  method.observe(stop({20.0, 5.0}, 100.0));
  const Vec2 robot{20.8, 4.3};
  const Vec2 goal = method.next(robot).goal;
  expect_at(goal, {20.3, 4.3 - kS60});
  EXPECT_NEAR(norm(goal - robot), 1.0, 1e-12);
}

TEST_F(PlumeTrackingTest, ZigzagFlipsOnDetectionBySeed000) {
  options.zigzag_flip = ZigzagFlip::OnDetection;
  Zigzag method(area, options);
  goal_after(method, {20.0, 4.0}, 100.0);  // the acquisition itself does not flip
  EXPECT_EQ(method.side(), 1);
  expect_at(goal_after(method, {19.5, 3.0}, 100.0), {19.0, 3.0 + kS60});
  EXPECT_EQ(method.side(), -1);
  goal_after(method, {19.0, 4.0}, 10.0);  // a non-detection does not flip
  EXPECT_EQ(method.side(), -1);
  goal_after(method, {18.5, 5.0}, 100.0);
  EXPECT_EQ(method.side(), 1);
}

TEST_F(PlumeTrackingTest, ZigzagFlipsAtTheWall) {
  Zigzag method(area, options);
  goal_after(method, {20.0, 4.0}, 100.0);
  // In the plume near the lower wall: the next leg (-y) would leave, so it flips.
  expect_at(goal_after(method, {19.5, 1.0}, 100.0), {19.0, 1.0 + kS60});
  EXPECT_EQ(method.side(), -1);
  // At the upwind wall both sides leave: it steps along the wall like the sweep.
  const Vec2 g = goal_after(method, {0.9, 4.0}, 100.0);
  EXPECT_TRUE(SearchBounds(area, 0.5).inside(g)) << to_string(g);
}

// The pseudo-gradient's p3 = centre of p1, p2 + 1.5 m at delta, beta = 90 deg.
TEST_F(PlumeTrackingTest, PseudoGradientTurnsTowardTheHigherReading) {
  PseudoGradient method(area, options);
  EXPECT_EQ(method.phase(), GradientPhase::Sweeping);
  // p1 = (20, 3) detects; the sweep direction points +y (toward the centre): p2 = (20, 4).
  expect_at(goal_after(method, {20.0, 3.0}, 300.0), {20.0, 4.0});
  EXPECT_EQ(method.phase(), GradientPhase::MeasureP2);
  // grad = 300 / 400 = 0.75 > 0.5: delta = upwind + 45 deg toward p1 (-y); the crosswind
  // direction inverts.
  const double r = 1.5 / std::sqrt(2.0);
  const Vec2 p3{20.0 - r, 3.5 - r};
  expect_at(goal_after(method, {20.0, 4.0}, 100.0), p3);
  EXPECT_EQ(method.phase(), GradientPhase::MeasureP1);
  expect_at(method.sweeper().direction(), {0.0, -1.0});
  // The next pair steps -y (the inverted direction): grad = 200 / 600 = 1/3 < 0.5 turns
  // 90 * (1 - 2/3) = 30 deg toward the new p2 (-y), where the seeds' inverted beta points.
  expect_at(goal_after(method, p3, 200.0), {p3.x, p3.y - 1.0});
  const Vec2 pc{p3.x, p3.y - 0.5};
  const Vec2 p3b = goal_after(method, {p3.x, p3.y - 1.0}, 400.0);
  expect_at(p3b, pc + 1.5 * heading(radians(210.0)));
  expect_at(method.sweeper().direction(), {0.0, -1.0});  // not inverted for grad < 0.5
}

TEST_F(PlumeTrackingTest, PseudoGradientLowerFirstReadingTurnsTowardP2) {
  PseudoGradient method(area, options);
  goal_after(method, {20.0, 3.0}, 100.0);
  // grad = 0.25: 45 deg toward p2 (+y), from the wind measured at p2.
  const double r = 1.5 / std::sqrt(2.0);
  expect_at(goal_after(method, {20.0, 4.0}, 300.0), {20.0 - r, 3.5 + r});
  expect_at(method.sweeper().direction(), {0.0, 1.0});
  // A reading at the threshold counts 0: grad = 0 turns the full beta, crosswind (+y).
  goal_after(method, {20.0, 5.0}, 50.0);
  expect_at(goal_after(method, {20.0, 6.0}, 300.0), {20.0, 5.5 + 1.5});
}

TEST_F(PlumeTrackingTest, PseudoGradientEqualReadingsFollowTheMeanWind) {
  PseudoGradient method(area, options);
  goal_after(method, {20.0, 3.0}, 200.0);
  // Upwind 180 deg at p1, 200 deg at p2 (wind at 20 deg): delta = 190 deg.
  const Vec2 g = goal_after(method, {20.0, 4.0}, 200.0, heading(radians(20.0)));
  expect_at(g, Vec2{20.0, 3.5} + 1.5 * heading(radians(190.0)));
  expect_at(method.sweeper().direction(), {0.0, 1.0});
}

TEST_F(PlumeTrackingTest, PseudoGradientBothZeroSweepsTheOtherWay) {
  PseudoGradient method(area, options);
  goal_after(method, {20.0, 3.0}, 200.0);
  const Vec2 p3 = goal_after(method, {20.0, 4.0}, 100.0);  // crosswind now -y
  goal_after(method, p3, 10.0);
  const Vec2 p2{p3.x, p3.y - 1.0};
  // Both below the threshold: the crosswind direction inverts (+y) and it sweeps from p2.
  expect_at(goal_after(method, p2, 20.0), {p2.x, p2.y + 1.0});
  EXPECT_EQ(method.phase(), GradientPhase::Sweeping);
  expect_at(method.sweeper().direction(), {0.0, 1.0});
}

TEST_F(PlumeTrackingTest, PseudoGradientStepsTheOtherWayAtTheWall) {
  PseudoGradient method(area, options);
  expect_at(goal_after(method, {20.0, 6.0}, 0.0), {20.0, 5.0});  // sweeping -y, to the centre
  // A detection at y = 1, where the crosswind step -y would leave: p2 lies +y instead.
  expect_at(goal_after(method, {20.0, 1.0}, 200.0), {20.0, 2.0});
  expect_at(method.sweeper().direction(), {0.0, 1.0});
}

TEST(DistanceOverhead, RatioOfTravelToProgress) {
  const Vec2 source{2.0, 4.0};
  // sqrt(2) + sqrt(2) + 1 travelled for 8 - 5 = 3 m of progress.
  const auto d = distance_overhead({{10.0, 4.0}, {9.0, 5.0}, {8.0, 4.0}, {7.0, 4.0}}, source);
  ASSERT_TRUE(d.has_value());
  EXPECT_NEAR(*d, (2.0 * std::sqrt(2.0) + 1.0) / 3.0, 1e-12);
  EXPECT_NEAR(*distance_overhead({{10.0, 4.0}, {4.0, 4.0}}, source), 1.0, 1e-12);
  EXPECT_FALSE(distance_overhead({{10.0, 4.0}, {10.0, 6.0}, {10.0, 4.0}}, source).has_value());
  EXPECT_FALSE(distance_overhead({}, source).has_value());
}

TEST_F(PlumeTrackingTest, OptionsOutOfRangeNameTheirField) {
  const auto field_of = [](TrackingOptions o) -> std::string {
    try {
      o.validate();
    } catch (const OptionError& e) {
      return e.field();
    }
    return "";
  };
  EXPECT_EQ(field_of(TrackingOptions{}), "");
  TrackingOptions o;
  o.step = 0.0;
  EXPECT_EQ(field_of(o), "tracking.step");
  o = {};
  o.detection_threshold = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(field_of(o), "tracking.detection_threshold");
  o = {};
  o.wall_margin = -0.1;
  EXPECT_EQ(field_of(o), "tracking.wall_margin");
  o = {};
  o.zigzag_alpha_deg = 90.0;
  EXPECT_EQ(field_of(o), "tracking.zigzag_alpha_deg");
  o = {};
  o.gradient_beta_deg = 91.0;
  EXPECT_EQ(field_of(o), "tracking.gradient_beta_deg");
  o = {};
  o.max_casts = 0;
  EXPECT_EQ(field_of(o), "tracking.max_casts");
  o = {};
  o.max_misses = 0;
  EXPECT_EQ(field_of(o), "tracking.max_misses");
  o = {};
  o.max_steps = 0;
  EXPECT_EQ(field_of(o), "tracking.max_steps");
  // A margin that leaves no room in the arena, and a bad option, at construction.
  const Map small = default_arena(2.0, 2.0);
  o = {};
  o.wall_margin = 1.0;
  EXPECT_THROW(SurgeCast(SearchArea{&small}, o), OptionError);
  o = {};
  o.step = -1.0;
  EXPECT_THROW(make_zigzag(area, o), OptionError);
  EXPECT_THROW(make_tracking_method("moth", area, options), OptionError);
  for (const auto& name : tracking_method_names())
    EXPECT_EQ(make_tracking_method(name, area, options)->name(), name);
}

TEST_F(PlumeTrackingTest, NonFiniteObservationIsAnInputError) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (const auto& name : tracking_method_names()) {
    auto method = make_tracking_method(name, area, options);
    EXPECT_THROW(method->observe(stop({nan, 4.0}, 0.0)), InputError) << name;
    EXPECT_THROW(method->observe(stop({20.0, 4.0}, inf)), InputError) << name;
    EXPECT_THROW(method->observe(stop({20.0, 4.0}, 0.0, {nan, 0.0})), InputError) << name;
  }
}

TEST_F(PlumeTrackingTest, CalmKeepsTheLastUpwindAndTheBudgetStops) {
  options.max_steps = 3;
  SurgeCast method(area, options);
  // No wind measured yet: upwind is -x.
  expect_at(goal_after(method, {20.0, 4.0}, 100.0, {0.0, 0.0}), {19.0, 4.0});
  // Wind toward +y: upwind -y; then a calm keeps -y.
  expect_at(goal_after(method, {19.0, 4.0}, 100.0, {0.0, 2.0}), {19.0, 3.0});
  EXPECT_EQ(method.stopped_by(), "");
  expect_at(goal_after(method, {19.0, 3.0}, 100.0, {0.0, 0.0}), {19.0, 2.0});
  EXPECT_EQ(method.stopped_by(), "max_samples");
  EXPECT_FALSE(method.estimate().has_value());
}

// A steady plume along +x from (2, 4): a Gaussian crosswind profile that widens downwind.
double fake_plume(Vec2 p) {
  const double dx = p.x - 2.0;
  if (dx <= 0.0) return 0.0;
  const double sigma = 0.2 + 0.05 * dx;
  const double dy = p.y - 4.0;
  return 1000.0 / (sigma * std::sqrt(2.0 * kPi)) * std::exp(-dy * dy / (2.0 * sigma * sigma));
}

// Drives a method as the runner would (to its goal, clamped to the arena) and returns the stops
// it took to come within 2 m of the source, or -1.
int stops_to_source(LocalizationMethod& method, Vec2 start, int budget) {
  const Vec2 source{2.0, 4.0};
  Vec2 robot = start;
  for (int k = 1; k <= budget && !method.stopped(); ++k) {
    if (norm(robot - source) <= 2.0) return k;
    method.observe(stop(robot, fake_plume(robot)));
    const Vec2 g = method.next(robot).goal;
    robot = {std::clamp(g.x, 0.0, 32.0), std::clamp(g.y, 0.0, 8.0)};
  }
  return -1;
}

TEST_F(PlumeTrackingTest, ClosedLoopTrackersReachTheSource) {
  // With beta = 90 deg a pair with one reading at or below the threshold moves straight
  // crosswind (Eq. 2), so in this steady plume, once it is narrower than about two steps, the
  // pseudo-gradient cycles across it; the seeds' real runs used 60 deg.
  options.gradient_beta_deg = 60.0;
  struct Case {
    const char* name;
    ZigzagFlip flip;
  };
  const Case cases[] = {{"surge-cast", ZigzagFlip::OnLoss},
                        {"zigzag", ZigzagFlip::OnLoss},
                        {"zigzag", ZigzagFlip::OnDetection},
                        {"pseudo-gradient", ZigzagFlip::OnLoss}};
  // (31, 4) lies in the plume; (31, 1) outside it, so the sweep must find it first.
  for (const Vec2 start : {Vec2{31.0, 4.0}, Vec2{31.0, 1.0}}) {
    for (const Case& c : cases) {
      options.zigzag_flip = c.flip;
      auto method = make_tracking_method(c.name, area, options);
      const int stops = stops_to_source(*method, start, 100);
      EXPECT_GT(stops, 0) << c.name << " from " << to_string(start);
      std::printf("%s%s from %s: %d stops\n", c.name,
                  c.flip == ZigzagFlip::OnDetection ? " (flip on detection)" : "",
                  to_string(start).c_str(), stops);
    }
  }
}

}  // namespace
}  // namespace plumekit::methods
