// Navigation over a floor of rooms: goals spread over the whole floor, ranked
// by expected gain per second, their tabulated readings, and the approximate
// expected gain they are scored with.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "../planner/test_maps.hpp"
#include "core/error.hpp"
#include "map/map.hpp"
#include "planner/free_space.hpp"
#include "ste/cached_readings.hpp"
#include "ste/grid_estimator.hpp"
#include "ste/navigation.hpp"
#include "ste/stop_rule.hpp"

namespace plumekit::ste {
namespace {

using planner::testing::two_rooms;

// Gas that stays in its room: a sensor reads 1000 exp(-d^2 / 2) from a source
// d metres away in the same room (either side of x = 4), nothing from the other.
class RoomPlume final : public SourceTableModel {
 public:
  explicit RoomPlume(const Map& map)
      : params_{{"x", 0, map.width}, {"y", 0, map.height}, {"release_scale", 1, 1}},
        grid_(GridShape::with_cell(map.width, map.height, 0.5)),
        ok_(free_cells(map, grid_, 0.0)) {}
  std::string name() const override { return "rooms"; }
  const std::vector<Parameter>& parameters() const override { return params_; }
  const GridShape& candidates() const override { return grid_; }
  const std::vector<std::uint8_t>& allowed() const override { return ok_; }
  std::vector<double> readings_at(Vec2 p) const override {
    ++calls;
    std::vector<double> r(grid_.size(), 0.0);
    for (int j = 0; j < grid_.ny; ++j)
      for (int i = 0; i < grid_.nx; ++i) {
        const Vec2 c = grid_.centre(i, j);
        const std::size_t k = grid_.index(i, j);
        if (ok_[k] && (c.x < 4.0) == (p.x < 4.0))
          r[k] = 1000.0 * std::exp(-0.5 * (c - p).x * (c - p).x - 0.5 * (c - p).y * (c - p).y);
      }
    return r;
  }
  mutable int calls = 0;

 private:
  std::vector<Parameter> params_;
  GridShape grid_;
  std::vector<std::uint8_t> ok_;
};

TEST(FloorNavigation, ARobotThatReadsNothingInItsRoomGoesToTheNextOne) {
  const Map map = two_rooms();
  const planner::FreeSpace space(map, 0.15, 8);
  const RoomPlume model(map);
  const GridShape bins = make_bins(map, {});
  GridEstimator est(model, {}, bins);
  // Nothing anywhere in the left room.
  for (const Vec2 p : {Vec2{1.0, 1.0}, Vec2{1.0, 3.0}, Vec2{3.0, 1.0}, Vec2{3.0, 3.0}, Vec2{2, 2}})
    est.add(p, 0.0);
  const Posterior post = est.posterior();
  const Vec2 robot{2.0, 2.0};

  NavigationOptions lattice;
  const Decision stay = Navigator(space, bins, lattice).decide(robot, est, post);
  EXPECT_LT(stay.goal.x, 4.0);  // the thesis's moves cannot leave the room

  NavigationOptions floor;
  floor.candidates = NavigationOptions::Candidates::Floor;
  const Navigator navigator(space, bins, floor);
  ASSERT_GT(navigator.floor_goals().size(), 20u);
  const Decision go = navigator.decide(robot, est, post);
  EXPECT_GT(go.goal.x, 4.1);
  EXPECT_TRUE(space.contains(go.goal));
  EXPECT_EQ(go.candidates.size(), go.gains.size());
  // The left room is known: what a sample there could still tell is next to nothing.
  const double best = *std::max_element(go.gains.begin(), go.gains.end());
  for (std::size_t c = 0; c < go.candidates.size(); ++c)
    if (go.candidates[c].x < 4.0) {
      EXPECT_LT(go.gains[c], 0.05 * best);
    }
}

TEST(FloorNavigation, NoGoalsAreFloorGoalsOnTheLattice) {
  const Map map = two_rooms();
  const planner::FreeSpace space(map, 0.15, 8);
  EXPECT_TRUE(Navigator(space, make_bins(map, {}), {}).floor_goals().empty());
  NavigationOptions bad;
  bad.floor_spacing = 0.0;
  EXPECT_THROW(Navigator(space, make_bins(map, {}), bad), OptionError);
}

TEST(SeenMass, ASourceWhosePlumeReachesNoSampleIsNotDeclared) {
  // Only the right room's 0.5 m strip by the far wall can hold the source, so one sample that
  // reads nothing in the left room leaves a posterior that is certain, and unseen.
  Map map = two_rooms();
  map.obstacles.push_back({{4.1, 0.0}, {7.5, 0.0}, {7.5, 4.0}, {4.1, 4.0}});
  const RoomPlume model(map);
  StopOptions stop;
  stop.entropy_fraction = 0.75;
  GridEstimator est(model, {}, make_bins(map, {}));
  for (const Vec2 p : {Vec2{1.0, 1.0}, Vec2{1.0, 3.0}, Vec2{3.0, 1.0}, Vec2{3.0, 3.0}, Vec2{2, 2}})
    est.add(p, 0.0);
  Posterior post = est.posterior();
  ASSERT_LT(post.entropy, stop.entropy_fraction * post.max_entropy);
  EXPECT_LT(post.seen_mass, 1e-9);
  EXPECT_EQ(stop_reason(post, est.samples(), stop), "");  // not declared: go on
  EXPECT_GT(post.expected_source().x, 7.5);
  stop.max_samples = 5;
  EXPECT_EQ(stop_reason(post, est.samples(), stop), "max_samples");

  // A sample in the strip that reads the source sees it: now the run may stop.
  stop.max_samples = 50;
  const int k = model.nearest_allowed({7.75, 2.25});
  est.add({7.75, 2.0}, model.readings_at({7.75, 2.0})[k]);
  post = est.posterior();
  EXPECT_GT(post.seen_mass, 0.95);
  EXPECT_EQ(stop_reason(post, est.samples(), stop), "entropy");
  stop.seen_mass = 0.0;  // the thesis's rule: entropy alone
  EXPECT_EQ(stop_reason(post, est.samples(), stop), "entropy");
}

TEST(CachedReadings, TabulatedPointsMatchTheModelAndOthersAreAskedOfIt) {
  const Map map = two_rooms();
  auto model = std::make_unique<RoomPlume>(map);
  const RoomPlume* raw = model.get();
  const std::vector<Vec2> points{{1.0, 1.0}, {6.5, 2.5}, {1.0, 1.0}};
  const CachedReadings cached(std::move(model), points, 2);
  EXPECT_EQ(raw->calls, 2);  // each distinct point once
  for (const Vec2 p : points) {
    const std::vector<double> want = raw->readings_at(p), got = cached.readings_at(p);
    ASSERT_EQ(got.size(), want.size());
    for (std::size_t k = 0; k < want.size(); ++k)
      EXPECT_NEAR(got[k], want[k], 1e-6 * std::abs(want[k]));  // float32
  }
  const int before = raw->calls;
  const std::vector<double> first = cached.readings_at({5.0, 1.0});
  EXPECT_EQ(raw->calls, before + 1);  // not tabulated: asked of the model
  EXPECT_EQ(cached.readings_at({5.0, 1.0}), first);
  EXPECT_EQ(raw->calls, before + 1);  // ... once: then remembered
  const std::vector<double> want = raw->readings_at({5.0, 1.0});
  for (std::size_t k = 0; k < want.size(); ++k)
    EXPECT_EQ(first[k], static_cast<double>(static_cast<float>(want[k])));
  EXPECT_EQ(cached.name(), "rooms");
  EXPECT_EQ(cached.allowed(), raw->allowed());
}

TEST(CachedReadings, RemembersTheMostRecentRowsWithinItsBudget) {
  const Map map = two_rooms();
  auto model = std::make_unique<RoomPlume>(map);
  const RoomPlume* raw = model.get();
  const double row_bytes = 4.0 * static_cast<double>(raw->candidates().size());
  const CachedReadings cached(std::move(model), {}, 1, 2.5 * row_bytes);  // two rows
  const Vec2 a{1.0, 1.0}, b{2.0, 1.0}, c{3.0, 1.0};
  const std::vector<double> ra = cached.readings_at(a);
  cached.readings_at(b);
  cached.readings_at(a);  // a is now the most recent, b the least
  EXPECT_EQ(raw->calls, 2);
  cached.readings_at(c);  // b goes
  cached.readings_at(a);
  EXPECT_EQ(raw->calls, 3);
  cached.readings_at(b);
  EXPECT_EQ(raw->calls, 4);
  // Remembered or asked again, a row is the same.
  EXPECT_EQ(cached.readings_at(a), ra);
  const CachedReadings forgetful(std::make_unique<RoomPlume>(map), {}, 1, 0.0);
  EXPECT_EQ(forgetful.readings_at(a), ra);
}

TEST(FloorNavigation, TheLatticesMovesLieOnAFixedGridInTheFloorMode) {
  const Map map = two_rooms();
  const planner::FreeSpace space(map, 0.15, 8);
  const RoomPlume model(map);
  const GridShape bins = make_bins(map, {});
  GridEstimator est(model, {}, bins);
  est.add({1.0, 1.0}, 0.0);
  const Posterior post = est.posterior();
  NavigationOptions floor;
  floor.candidates = NavigationOptions::Candidates::Floor;
  const Navigator navigator(space, bins, floor);
  // Two robots a few centimetres apart see the same moves, and every floor goal near them is one.
  const Decision a = navigator.decide({2.02, 1.97}, est, post);
  const Decision b = navigator.decide({1.95, 2.04}, est, post);
  const auto moves = [](const Decision& d) {
    return std::vector<Vec2>(d.candidates.begin(), d.candidates.begin() + 24);
  };
  ASSERT_GE(a.candidates.size(), 24u);
  EXPECT_EQ(moves(a), moves(b));
  int goals_among_moves = 0;
  for (const Vec2& g : navigator.floor_goals())
    goals_among_moves += std::count(a.candidates.begin(), a.candidates.begin() + 24, g) > 0;
  EXPECT_GE(goals_among_moves, 4);
  // The thesis's lattice stays around the robot itself.
  const Decision thesis = Navigator(space, bins, {}).decide({2.02, 1.97}, est, post);
  EXPECT_EQ(thesis.candidates.front(), (Vec2{2.02 - 1.0, 1.97 - 1.0}));
}

TEST(FloorGain, ResampledSupportKeepsTheMassAndApproximatesTheExactGain) {
  std::vector<double> w(1000);
  double sum = 0.0;
  for (std::size_t k = 0; k < w.size(); ++k)
    sum += (w[k] = 1.0 + std::sin(0.1 * k));
  for (double& v : w)
    v /= sum;
  for (const int cap : {64, 999, 1000}) {
    const auto support = GridEstimator::gain_support(w, cap);
    double mass = 0.0;
    for (const auto& [k, weight] : support)
      mass += weight;
    EXPECT_NEAR(mass, 1.0, 1e-12) << cap;
    EXPECT_LE(support.size(), static_cast<std::size_t>(cap));
    if (cap == 1000) {
      EXPECT_EQ(support.size(), 1000u);  // exact: every cell with mass
    }
  }

  const Map map = two_rooms();
  const RoomPlume model(map);
  GridEstimator est(model, {}, make_bins(map, {}));
  est.add({2.0, 2.0}, 0.0);
  const Posterior post = est.posterior();
  const std::vector<Vec2> points{{1.0, 1.0}, {6.0, 2.0}, {7.5, 0.5}, {3.5, 3.5}};
  const std::vector<double> exact = est.expected_information_gains(points, post, 0);
  const std::vector<double> rough = est.expected_information_gains(points, post, 32);
  // Within 15 % where a point is informative; a point that tells next to nothing may miss the
  // few cells that it tells about.
  const double most = *std::max_element(exact.begin(), exact.end());
  ASSERT_GT(most, 0.1);
  for (std::size_t i = 0; i < points.size(); ++i) {
    EXPECT_NEAR(exact[i], est.expected_information_gain(points[i], post), 1e-12);
    EXPECT_NEAR(rough[i], exact[i], 0.15 * exact[i] + 0.02 * most) << i;
  }
}

}  // namespace
}  // namespace plumekit::ste

namespace plumekit::ste {
namespace {

TEST(PathScoring, AGoalGainsWhatItsPathPassesTimesTheShareOfAStop) {
  // Roadmap nodes 0 <- 1 <- 2 <- 3 (0 the root) and 4 <- 1; goals at nodes 1, 2, 3 and 4.
  const std::vector<int> previous{-1, 0, 1, 2, 1};
  const std::vector<int> node{1, 2, 3, 4};
  const std::vector<double> gain{0.4, 0.2, 0.1, 0.8};
  const std::vector<double> s = gains_along_paths(node, gain, previous, 0.5);
  ASSERT_EQ(s.size(), 4u);
  EXPECT_DOUBLE_EQ(s[0], 0.0);                // nothing before node 1 but the root
  EXPECT_DOUBLE_EQ(s[1], 0.5 * 0.4);          // passes node 1
  EXPECT_DOUBLE_EQ(s[2], 0.5 * (0.2 + 0.4));  // passes 2 and 1
  EXPECT_DOUBLE_EQ(s[3], 0.5 * 0.4);          // its own branch passes 1 only
  // Without readings on the way a path reads nothing.
  for (double x : gains_along_paths(node, gain, previous, 0.0))
    EXPECT_EQ(x, 0.0);
}

}  // namespace
}  // namespace plumekit::ste
