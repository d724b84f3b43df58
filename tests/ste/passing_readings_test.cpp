// Readings taken on the way (ste/passing_readings.hpp): stretches averaged into partial samples,
// their weights and places, and what a partial sample does to the posterior.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "map/map.hpp"
#include "ste/cached_readings.hpp"
#include "ste/grid_estimator.hpp"
#include "ste/passing_readings.hpp"

namespace plumekit::ste {
namespace {

// A robot driving along x at 0.5 m/s from (1, 2), reading 10 times a second: reading k at time
// 0.1 (k + 1) s (each reading ends its interval), at x = 1 + 0.05 (k + 1), valued k.
std::vector<PassingReading> drive(int n) {
  std::vector<PassingReading> r;
  for (int k = 0; k < n; ++k)
    r.push_back({{1.0 + 0.05 * (k + 1), 2.0}, 0.1 * (k + 1), static_cast<double>(k)});
  return r;
}

TEST(PassingReadings, StretchesOfAWindowAreAveragedAndWeighAsTheirShareOfAStop) {
  PassingOptions o;  // 1 s windows, 0.1 s readings, 5 s stops, no lag
  const std::vector<PartialSample> s = partial_samples(drive(25), o);
  ASSERT_EQ(s.size(), 3u);
  EXPECT_DOUBLE_EQ(s[0].value, 4.5);  // the mean of 0..9
  EXPECT_DOUBLE_EQ(s[1].value, 14.5);
  EXPECT_DOUBLE_EQ(s[2].value, 22.0);  // 20..24
  EXPECT_DOUBLE_EQ(s[0].weight, 0.2);
  EXPECT_DOUBLE_EQ(s[2].weight, 0.1);
  // The middle of the first second (0.5 s) is where the robot was then: x = 1.25.
  EXPECT_NEAR(s[0].position.x, 1.25, 1e-12);
  EXPECT_NEAR(s[1].position.x, 1.75, 1e-12);
  // A sensor 0.4 s late reports what it met 0.2 m earlier.
  o.lag_s = 0.4;
  const std::vector<PartialSample> late = partial_samples(drive(25), o);
  EXPECT_NEAR(late[1].position.x, 1.55, 1e-12);
  // Before the first reading, the first reading's point (where the robot set out).
  EXPECT_NEAR(late[0].position.x, 1.05, 1e-12);
  // A window longer than a stop still counts as one stop at most.
  o.window_s = 10.0;
  EXPECT_DOUBLE_EQ(partial_samples(drive(80), o).front().weight, 1.0);
}

TEST(PassingReadings, AGapInTheReadingsStartsANewStretch) {
  std::vector<PassingReading> r = drive(6);
  for (PassingReading& x : r)
    if (x.time_s > 0.35) x.time_s += 1.0;  // a second with no reading after the third
  const std::vector<PartialSample> s = partial_samples(r, PassingOptions{});
  ASSERT_EQ(s.size(), 2u);
  EXPECT_DOUBLE_EQ(s[0].value, 1.0);  // 0, 1, 2
  EXPECT_DOUBLE_EQ(s[1].value, 4.0);  // 3, 4, 5
  EXPECT_TRUE(partial_samples({}, PassingOptions{}).empty());
}

TEST(PassingReadings, BadReadingsAndOptionsAreNamed) {
  std::vector<PassingReading> r = drive(5);
  r[3].value = std::numeric_limits<double>::quiet_NaN();
  try {
    partial_samples(r, PassingOptions{});
    FAIL() << "a NaN reading was taken";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("reading 3"), std::string::npos) << e.what();
  }
  PassingOptions o;
  o.window_s = 0.0;
  EXPECT_THROW(partial_samples(drive(5), o), InputError);
  o = {};
  o.lag_s = -1.0;
  EXPECT_THROW(o.validate(), InputError);
}

// One candidate per 0.5 m cell reading 1000 exp(-d^2 / 2) at distance d.
class Bump final : public SourceTableModel {
 public:
  explicit Bump(const Map& map)
      : params_{{"x", 0, map.width}, {"y", 0, map.height}, {"release_scale", 1, 1}},
        grid_(GridShape::with_cell(map.width, map.height, 0.5)),
        ok_(free_cells(map, grid_, 0.0)) {}
  std::string name() const override { return "bump"; }
  const std::vector<Parameter>& parameters() const override { return params_; }
  const GridShape& candidates() const override { return grid_; }
  const std::vector<std::uint8_t>& allowed() const override { return ok_; }
  std::vector<double> readings_at(Vec2 p) const override {
    std::vector<double> r(grid_.size(), 0.0);
    for (int j = 0; j < grid_.ny; ++j)
      for (int i = 0; i < grid_.nx; ++i) {
        const Vec2 d = grid_.centre(i, j) - p;
        r[grid_.index(i, j)] = 1000.0 * std::exp(-0.5 * dot(d, d));
      }
    return r;
  }

 private:
  std::vector<Parameter> params_;
  GridShape grid_;
  std::vector<std::uint8_t> ok_;
};

TEST(PassingReadings, APartialSampleIsItsShareOfASampleAndNoStop) {
  const Map map = default_arena(6.0, 4.0);
  const Bump model(map);
  LikelihoodOptions l;
  l.sigma_m = 100.0;
  const GridShape bins = make_bins(map, {});
  GridEstimator whole(model, l, bins), halves(model, l, bins), full_partial(model, l, bins);
  whole.add({2.0, 2.0}, 600.0);
  halves.add_partial({2.0, 2.0}, 600.0, 0.5);
  halves.add_partial({2.0, 2.0}, 600.0, 0.5);
  full_partial.add_partial({2.0, 2.0}, 600.0, 1.0);
  EXPECT_EQ(whole.samples(), 1);
  EXPECT_EQ(halves.samples(), 0);  // the stops' count, which the sample budget reads
  const Posterior a = whole.posterior(), b = halves.posterior(), c = full_partial.posterior();
  for (std::size_t k = 0; k < a.marginal.values.size(); ++k) {
    EXPECT_NEAR(a.marginal.values[k], b.marginal.values[k], 1e-12) << k;
    EXPECT_EQ(a.marginal.values[k], c.marginal.values[k]) << k;
  }
  // A weaker partial sample moves the posterior less: its entropy stays higher.
  GridEstimator tenth(model, l, bins);
  tenth.add_partial({2.0, 2.0}, 600.0, 0.1);
  EXPECT_GT(tenth.posterior().entropy, a.entropy);
  EXPECT_THROW(tenth.add_partial({2.0, 2.0}, 600.0, 0.0), InputError);
  EXPECT_THROW(tenth.add_partial({2.0, 2.0}, 600.0, 1.5), InputError);
}

}  // namespace
}  // namespace plumekit::ste
