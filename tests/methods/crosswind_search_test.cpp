// The surge-spiral and surge-cast trackers of seed 004 ch. 17 in the wind tunnel: the spiral and
// cast geometry after a loss, the surge, the Lévy acquisition's move lengths, the in-plume
// threshold's quantile rule, and that goals stay in the tunnel a step apart.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "core/error.hpp"
#include "methods/crosswind_search.hpp"

namespace plumekit::methods {
namespace {

constexpr double kTwoPi = 6.283185307179586;
const Box3 kTunnel{{0.0, -2.0, 0.0}, {16.0, 2.0, 2.0}};

CrosswindSearchOptions options_for(CrosswindMode mode) {
  CrosswindSearchOptions o;
  o.mode = mode;
  o.altitude = 1.0;
  return o;
}

// Surges once, then loses the plume where the robot stands: the loss point.
Vec3 lose_plume_at(CrosswindSearch& search, Vec3 robot) {
  search.observe({robot, 100.0, {1.0, 0.0, 0.0}, 0.0, 1.0});
  EXPECT_EQ(search.phase(), "surge");
  search.observe({robot, 0.0, {1.0, 0.0, 0.0}, 0.0, 2.0});
  return robot;
}

// Eq. 17.3: the goals stay at x_c, at the angle 2 pi t and the distance s_d t from the loss point
// (t recovered from the unwrapped angle, so the radius grows by s_d per turn), each `step` along
// the arc from the last: the chord is a little shorter near the centre, nearly the step outside.
TEST(CrosswindSearchSpiral, GoalsFollowTheArchimedeanSpiralAStepApart) {
  CrosswindSearch search(kTunnel, options_for(CrosswindMode::Spiral3d), 3);
  const Vec3 c = lose_plume_at(search, {8.0, 0.3, 1.1});
  EXPECT_EQ(search.phase(), "spiral");
  Vec3 robot = c;
  double unwrapped = 0.0, last_angle = 0.0;
  double path = 0.0;
  const int decisions = 120;
  for (int k = 0; k < decisions; ++k) {
    const Vec3 g = search.next(robot).goal;
    ASSERT_EQ(g.x, c.x);
    const double dy = g.y - c.y, dz = g.z - c.z;
    const double angle = std::atan2(dz, dy);
    double turn = angle - last_angle;
    if (turn < -kTwoPi / 2) turn += kTwoPi;
    ASSERT_GT(turn, 0.0) << k;  // counter-clockwise in y-z, never back
    unwrapped += turn;
    last_angle = angle;
    const double t = unwrapped / kTwoPi;
    EXPECT_NEAR(std::hypot(dy, dz), 0.1 * t, 1e-9) << k;
    EXPECT_NEAR(search.spiral_t(), t, 1e-9) << k;
    const double chord = norm(g - robot);
    EXPECT_LE(chord, 0.05 + 1e-12) << k;
    EXPECT_GT(chord, 0.03) << k;
    if (t > 1.0) {
      EXPECT_GT(chord, 0.049) << k;  // 2 R sin(step / 2R), R >= 0.1
    }
    if (t > 3.0) {
      EXPECT_GT(chord, 0.0499) << k;
    }
    path += chord;
    robot = g;
  }
  // 120 steps of 0.05 m of arc: 6 m, where the arc's closed form gives t = 4.3571 (4.36 turns,
  // 0.4357 m from the loss point).
  EXPECT_NEAR(search.spiral_t(), 4.3571, 1e-4);
  EXPECT_NEAR(norm(robot - c), 0.43571, 1e-5);
  EXPECT_GT(path, 0.99 * decisions * 0.05);
  // The plume again: surge; the next loss starts a fresh spiral from its own point.
  search.observe({robot, 100.0, {1.0, 0.0, 0.0}, 0.0, 3.0});
  EXPECT_EQ(search.phase(), "surge");
  robot = search.next(robot).goal;
  search.observe({robot, 0.0, {1.0, 0.0, 0.0}, 0.0, 4.0});
  EXPECT_EQ(search.phase(), "spiral");
  EXPECT_EQ(search.loss_point().x, robot.x);
  const Vec3 g = search.next(robot).goal;
  EXPECT_EQ(g.x, robot.x);
  EXPECT_NEAR(search.spiral_t(), 0.33118, 1e-5);  // the first 0.05 m of arc
}

// Lochmatter's casting at a fixed altitude: legs to y_c + D, y_c - 2D, y_c + 3D, ... at x_c,
// walked a step at a time, every goal at the altitude.
TEST(CrosswindSearchCast, LegsAlternateAndWidenAtTheAltitude) {
  CrosswindSearchOptions o = options_for(CrosswindMode::Cast2d);
  o.altitude = 0.8;
  const Box3 wide{{0.0, -10.0, 0.0}, {16.0, 10.0, 2.0}};
  CrosswindSearch search(wide, o, 3);
  const Vec3 c = lose_plume_at(search, {8.0, 0.2, 0.8});
  EXPECT_EQ(search.phase(), "cast");
  std::vector<double> ends;
  Vec3 robot = c;
  for (int k = 0; k < 400 && ends.size() < 6; ++k) {
    const Vec3 g = search.next(robot).goal;
    ASSERT_EQ(g.x, 8.0);
    ASSERT_EQ(g.z, 0.8);
    ASSERT_LE(norm(g - robot), 0.05 + 1e-12);
    if (ends.empty() || search.waypoint().y != ends.back()) ends.push_back(search.waypoint().y);
    robot = g;
  }
  const std::vector<double> expected = {0.63, -0.66, 1.49, -1.52, 2.35, -2.38};
  ASSERT_EQ(ends.size(), expected.size());
  for (std::size_t k = 0; k < ends.size(); ++k)
    EXPECT_NEAR(ends[k], expected[k], 1e-12) << k;
}

// Surge: one step against the wind's direction, whichever way it blows; Cast2d uses its x-y part
// at the altitude; a calm surges along -x.
TEST(CrosswindSearchSurge, StepsUpwindAgainstAnObliqueWind) {
  const Vec3 robot{8.0, 0.5, 1.2};
  const Vec3 wind{1.0, 0.5, -0.2};  // |wind| = sqrt(1.29)
  CrosswindSearch spiral(kTunnel, options_for(CrosswindMode::Spiral3d), 1);
  spiral.observe({robot, 50.0, wind, 0.0, 1.0});
  EXPECT_EQ(spiral.phase(), "surge");
  Vec3 g = spiral.next(robot).goal;
  const double s = 0.05 / std::sqrt(1.29);
  EXPECT_NEAR(g.x, 8.0 - s, 1e-12);
  EXPECT_NEAR(g.y, 0.5 - 0.5 * s, 1e-12);
  EXPECT_NEAR(g.z, 1.2 + 0.2 * s, 1e-12);
  EXPECT_NEAR(g.x, 7.9559775, 1e-7);

  CrosswindSearch cast(kTunnel, options_for(CrosswindMode::Cast2d), 1);
  cast.observe({{8.0, 0.5, 1.0}, 50.0, wind, 0.0, 1.0});
  g = cast.next({8.0, 0.5, 1.0}).goal;
  const double h = 0.05 / std::sqrt(1.25);
  EXPECT_NEAR(g.x, 8.0 - h, 1e-12);
  EXPECT_NEAR(g.y, 0.5 - 0.5 * h, 1e-12);
  EXPECT_EQ(g.z, 1.0);

  spiral.observe({robot, 50.0, {0.0, 0.0, 0.0}, 0.0, 2.0});
  g = spiral.next(robot).goal;
  EXPECT_NEAR(g.x, 7.95, 1e-12);
  EXPECT_EQ(g.y, 0.5);
  EXPECT_EQ(g.z, 1.2);
}

// Eq. 17.1 with mu = 3: P(M > x) = (x / L_min)^-2, whose median is L_min sqrt(2) = 0.7071 m. A
// step longer than the longest move reaches each target in one decision, and a large tunnel
// keeps the clamp away, so each goal is one draw from where the robot stands.
TEST(CrosswindSearchLevy, MoveLengthsHaveThePowerLawsMedian) {
  const Box3 huge{{0.0, -1000.0, -1000.0}, {100.0, 1000.0, 1000.0}};
  for (CrosswindMode mode : {CrosswindMode::Spiral3d, CrosswindMode::Cast2d}) {
    CrosswindSearchOptions o = options_for(mode);
    o.step = 5.0;
    o.altitude = 0.0;
    CrosswindSearch search(huge, o, 11);
    Vec3 robot{50.0, 0.0, 0.0};
    std::vector<double> lengths;
    int up = 0, right = 0;
    const int n = 4001;
    for (int k = 0; k < n; ++k) {
      const Vec3 g = search.next(robot).goal;
      ASSERT_EQ(search.phase(), "levy");
      ASSERT_EQ(g.x, 50.0);
      const Vec3 d = g - robot;
      lengths.push_back(norm(d));
      up += d.z > 0.0;
      right += d.y > 0.0;
      if (mode == CrosswindMode::Cast2d) {
        ASSERT_EQ(g.z, 0.0);
      }
      robot = g;
    }
    std::sort(lengths.begin(), lengths.end());
    EXPECT_NEAR(lengths[n / 2], 0.5 * std::sqrt(2.0), 0.03);
    EXPECT_NEAR(lengths.front(), 0.5, 1e-3);
    EXPECT_LE(lengths.back(), 4.0 + 1e-12);
    EXPECT_NEAR(lengths[n * 9 / 10], 0.5 * std::sqrt(10.0), 0.1);  // P(M > x) = 0.1
    EXPECT_NEAR(right / double(n), 0.5, 0.03);
    if (mode == CrosswindMode::Spiral3d) {
      EXPECT_NEAR(up / double(n), 0.5, 0.03);
    }
  }
}

// Whatever the readings, in a tunnel barely larger than a move: every goal inside it, at most a
// step from the robot, even from a start against a wall.
TEST(CrosswindSearch, GoalsStayInsideTheTunnel) {
  const Box3 small{{0.0, 0.0, 0.0}, {2.0, 1.0, 0.6}};
  for (CrosswindMode mode : {CrosswindMode::Spiral3d, CrosswindMode::Cast2d}) {
    CrosswindSearchOptions o = options_for(mode);
    o.altitude = 0.3;
    o.calibration = 5;
    CrosswindSearch search(small, o, 5);
    Vec3 robot{2.0, 1.0, mode == CrosswindMode::Cast2d ? 0.3 : 0.6};
    int phases[4] = {0, 0, 0, 0};
    for (int k = 0; k < 3000; ++k) {
      // Bursts of gas and long gaps, as in an intermittent plume.
      const double gas = (k / 37) % 3 == 0 ? 20.0 + (k % 7) * 10.0 : (k % 5);
      search.observe({robot, gas, {1.0, 0.3 * std::sin(0.1 * k), 0.1}, 0.0, double(k)});
      const std::string p = search.phase();
      phases[p == "levy" ? 0 : p == "surge" ? 1 : p == "spiral" ? 2 : 3]++;
      const Vec3 g = search.next(robot).goal;
      ASSERT_TRUE(small.contains(g)) << k;
      ASSERT_LE(norm(g - robot), o.step + 1e-12) << k;
      if (mode == CrosswindMode::Cast2d) {
        ASSERT_EQ(g.z, 0.3);
      }
      robot = g;
    }
    EXPECT_GT(phases[1], 0);
    EXPECT_GT(mode == CrosswindMode::Spiral3d ? phases[2] : phases[3], 1000);
  }
}

// The highest 70 % (90 %) of the first 20 readings of gas are in the plume: with readings
// 10, 20, ..., 200 the 30 % quantile is 60 + 0.7 * 10 = 67 (14 readings above), the 10 % one
// 20 + 0.9 * 10 = 29. Readings below the detection limit do not count; the threshold is the
// detection limit until the 20th reading of gas, fixed after it.
TEST(CrosswindSearchThreshold, TheQuantileRuleOnHandComputedReadings) {
  double thresholds[2];
  for (int m = 0; m < 2; ++m) {
    CrosswindSearchOptions o = options_for(CrosswindMode::Spiral3d);
    o.threshold = m == 0 ? 0.7 : 0.9;
    CrosswindSearch search(kTunnel, o, 1);
    const Vec3 at{8.0, 0.0, 1.0};
    for (double low : {1.0, 4.9, 0.0})
      search.observe({at, low, {1.0, 0.0, 0.0}, 0.0, 0.0});
    EXPECT_DOUBLE_EQ(search.threshold(), 5.0);
    for (int k = 0; k < 20; ++k) {
      EXPECT_FALSE(search.calibrated());
      search.observe({at, 10.0 * ((k * 7) % 20 + 1), {1.0, 0.0, 0.0}, 0.0, 0.0});  // shuffled
    }
    EXPECT_TRUE(search.calibrated());
    thresholds[m] = search.threshold();
    search.observe({at, 1000.0, {1.0, 0.0, 0.0}, 0.0, 0.0});
    search.observe({at, 5.0, {1.0, 0.0, 0.0}, 0.0, 0.0});
    EXPECT_DOUBLE_EQ(search.threshold(), thresholds[m]);  // fixed
    search.observe({at, 50.0, {1.0, 0.0, 0.0}, 0.0, 0.0});
    EXPECT_EQ(search.phase(), m == 0 ? "spiral" : "surge");
  }
  EXPECT_NEAR(thresholds[0], 67.0, 1e-12);
  EXPECT_NEAR(thresholds[1], 29.0, 1e-12);
  EXPECT_LT(thresholds[1], thresholds[0]);
}

TEST(CrosswindSearch, SameSeedSameGoals) {
  const auto run = [](std::uint64_t seed) {
    CrosswindSearch search(kTunnel, options_for(CrosswindMode::Spiral3d), seed);
    Vec3 robot{8.0, 0.0, 1.0};
    std::vector<double> coordinates;
    for (int k = 0; k < 200; ++k) {
      search.observe({robot, k % 60 >= 50 ? 40.0 : 0.0, {1.0, 0.0, 0.0}, 0.0, double(k)});
      robot = search.next(robot).goal;
      coordinates.insert(coordinates.end(), {robot.x, robot.y, robot.z});
    }
    return coordinates;
  };
  EXPECT_EQ(run(42), run(42));
  EXPECT_NE(run(42), run(43));
}

TEST(CrosswindSearch, RefusesNanOptionsAndObservationsNamingTheField) {
  const double nan = std::nan("");
  const auto field_of = [](const CrosswindSearchOptions& o) -> std::string {
    try {
      o.validate();
    } catch (const OptionError& e) {
      return e.field();
    }
    return "";
  };
  CrosswindSearchOptions o;
  EXPECT_EQ(field_of(o), "");
  const std::vector<std::pair<double CrosswindSearchOptions::*, std::string>> fields = {
      {&CrosswindSearchOptions::step, "step"},
      {&CrosswindSearchOptions::levy_mu, "levy_mu"},
      {&CrosswindSearchOptions::levy_min, "levy_min"},
      {&CrosswindSearchOptions::levy_max, "levy_max"},
      {&CrosswindSearchOptions::spiral_drift, "spiral_drift"},
      {&CrosswindSearchOptions::cast, "cast"},
      {&CrosswindSearchOptions::threshold, "threshold"},
      {&CrosswindSearchOptions::detection, "detection"},
      {&CrosswindSearchOptions::altitude, "altitude"}};
  for (const auto& [member, name] : fields) {
    CrosswindSearchOptions bad;
    bad.*member = nan;
    EXPECT_EQ(field_of(bad), "tunnel.search." + name);
  }
  o.threshold = 1.2;
  EXPECT_EQ(field_of(o), "tunnel.search.threshold");
  o = {};
  o.calibration = 0;
  EXPECT_EQ(field_of(o), "tunnel.search.calibration");
  o = options_for(CrosswindMode::Cast2d);
  o.altitude = 2.5;  // above the tunnel
  EXPECT_THROW(CrosswindSearch(kTunnel, o, 1), OptionError);

  CrosswindSearch search(kTunnel, {}, 1);
  const auto message_of = [&](const Observation3& obs) -> std::string {
    try {
      search.observe(obs);
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_NE(message_of({{8.0, 0.0, 1.0}, nan, {1.0, 0.0, 0.0}, 0.0, 0.0}).find("gas"),
            std::string::npos);
  EXPECT_NE(message_of({{8.0, 0.0, 1.0}, -1.0, {1.0, 0.0, 0.0}, 0.0, 0.0}).find("gas is negative"),
            std::string::npos);
  EXPECT_NE(message_of({{8.0, 0.0, 1.0}, 1.0, {1.0, nan, 0.0}, 0.0, 0.0}).find("wind.y"),
            std::string::npos);
  EXPECT_NE(message_of({{8.0, nan, 1.0}, 1.0, {1.0, 0.0, 0.0}, 0.0, 0.0}).find("position.y"),
            std::string::npos);
  EXPECT_NE(message_of({{8.0, 0.0, 1.0}, 1.0, {1.0, 0.0, 0.0}, 0.0, nan}).find("time_s"),
            std::string::npos);
  EXPECT_EQ(message_of({{8.0, 0.0, 1.0}, 1.0, {1.0, 0.0, 0.0}, 0.0, 0.0}), "");
}

}  // namespace
}  // namespace plumekit::methods
