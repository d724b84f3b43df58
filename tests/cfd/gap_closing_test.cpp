// Narrow gaps (cfd/gap_closing.hpp) and the default cell (cfd/options.hpp).
#include "cfd/gap_closing.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "cfd/flow_solver.hpp"
#include "cfd/grid_check.hpp"
#include "cfd/options.hpp"
#include "core/error.hpp"
#include "map/rasterize.hpp"

namespace plumekit::cfd {
namespace {

Polygon box(double x0, double y0, double x1, double y1) {
  return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
}

void expect_has(const std::string& text, const std::string& part) {
  EXPECT_NE(text.find(part), std::string::npos) << "'" << part << "' not in: " << text;
}

std::string option_error(const Map& map, const FlowOptions& o) {
  try {
    solve(map, o);
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "flow.cell");
    return e.what();
  }
  ADD_FAILURE() << "no OptionError";
  return "";
}

// A 4 x 2 m arena with two gaps between blocks: 0.03 m (obstacles 0 and 1;
// 10 cm cells have a centre in it, at y = 0.95) and, found later in index
// order, 0.012 m (obstacles 2 and 3).
Map two_gaps() {
  Map map = default_arena(4.0, 2.0);
  map.obstacles = {box(1.0, 0.4, 1.5, 0.94), box(1.0, 0.97, 1.5, 1.5),   // 0.03 apart in y
                   box(2.5, 0.4, 3.0, 1.0), box(3.012, 0.4, 3.5, 1.0)};  // 0.012 apart in x
  return map;
}

TEST(GapClosing, GapsNarrowerThanACellAreReportedNarrowestFirst) {
  const Map map = two_gaps();
  const GridShape shape = GridShape::with_cell(4.0, 2.0, 0.05);
  const std::vector<GapReport> gaps = find_narrow_gaps(map, shape);
  ASSERT_EQ(gaps.size(), 2u);
  EXPECT_EQ(gaps[0].a, 2);
  EXPECT_EQ(gaps[0].b, 3);
  EXPECT_NEAR(gaps[0].width, 0.012, 1e-12);
  EXPECT_NEAR(gaps[0].at.x, 3.006, 1e-12);  // midway across the gap,
  EXPECT_NEAR(gaps[0].at.y, 0.7, 1e-12);    // and along the edges facing each other
  EXPECT_EQ(gaps[1].a, 0);
  EXPECT_NEAR(gaps[1].width, 0.03, 1e-12);
  // An obstacle 0.02 m from the top wall is a gap too.
  Map walled = map;
  walled.obstacles.push_back(box(0.2, 1.5, 0.6, 1.98));
  const std::vector<GapReport> w = find_narrow_gaps(walled, shape);
  ASSERT_EQ(w.size(), 3u);
  EXPECT_EQ(w[1].a, 4);
  ASSERT_TRUE(w[1].wall.has_value());
  EXPECT_EQ(*w[1].wall, Side::Top);
  EXPECT_NEAR(w[1].width, 0.02, 1e-12);
  EXPECT_NEAR(w[1].at.x, 0.4, 1e-12);  // the middle of the edge along the wall
  EXPECT_NEAR(w[1].at.y, 1.99, 1e-12);
}

TEST(GapClosing, ClosedGapCellsAreSolidWhereverTheCellsFall) {
  // A wall across the arena split by a 0.03 m gap, at offsets that put a cell
  // centre in the gap (an open one-cell channel in the plain rasterization) or not.
  for (double offset : {0.0, 0.01, 0.02, 0.03, 0.04}) {
    Map map = default_arena(4.0, 2.0);
    const double y = 0.9 + offset;
    map.obstacles = {box(1.0, 0.0, 1.5, y), box(1.0, y + 0.03, 1.5, 2.0)};
    const GridShape shape = GridShape::with_cell(4.0, 2.0, 0.05);
    Grid<std::uint8_t> solid = rasterize_occupancy(map, shape);
    const std::vector<GapReport> gaps = close_narrow_gaps(map, shape, solid.values);
    ASSERT_EQ(gaps.size(), 1u) << offset;
    EXPECT_FALSE(inlet_reaches_outlet(rasterize_labels(map, solid))) << offset;
    // Free cells away from the gap stay free.
    EXPECT_EQ(solid(10, 20), 0);
    EXPECT_EQ(solid(40, 20), 0);
  }
}

TEST(GapClosing, TheSolverClosesTheGapAndReportsItInTheMapFrame) {
  Map map = two_gaps();
  map.frame.origin = {100.0, -20.0};
  FlowOptions o;
  o.cell = 0.1;
  o.nu = 0.05;
  const FlowResult r = solve(map, o);
  EXPECT_EQ(r.summary.closed_gaps.count, 2);
  ASSERT_EQ(r.summary.closed_gaps.narrowest.size(), 2u);
  const ClosedGap& g = r.summary.closed_gaps.narrowest[0];
  EXPECT_EQ(g.between, "obstacles[2] and obstacles[3]");
  EXPECT_NEAR(g.width, 0.012, 1e-12);
  EXPECT_NEAR(g.at.x, 103.006, 1e-9);
  EXPECT_NEAR(g.at.y, -19.3, 1e-9);
  // 0.012 m gives 333 cells on 4 m, 0.012012 m each: too wide.
  EXPECT_NEAR(r.summary.closed_gaps.open_cell, 0.011, 1e-12);
  // The cell centred in the 0.03 m gap, (1.25, 0.95): free in the plain
  // rasterization, solid in the solved grid.
  EXPECT_EQ(rasterize_occupancy(map, r.wind.shape())(12, 9), 0);
  EXPECT_TRUE(r.wind.solid(12, 9));
  EXPECT_LT(r.summary.mass_imbalance, 1e-6);
  expect_has(closed_gaps_text(r.summary.closed_gaps, 0.1),
             "closed 2 gaps narrower than the 0.1 m cell (open in the map): obstacles[2] and "
             "obstacles[3], 0.012 m apart at (103.006, -19.3)");
}

// The gap and thin-wall reports place what they name to the millimetre, however far from the
// origin, without trailing zeros and without a "-0".
TEST(GapClosing, CoordinatesAreWrittenToTheMillimetre) {
  EXPECT_EQ(millimetre_coordinate(103.006), "103.006");
  EXPECT_EQ(millimetre_coordinate(-19.6), "-19.6");
  EXPECT_EQ(millimetre_coordinate(2.0), "2");
  EXPECT_EQ(millimetre_coordinate(12345.67849), "12345.678");
  EXPECT_EQ(millimetre_coordinate(-0.0004), "0");
  EXPECT_EQ(millimetre_coordinate(0.0), "0");
}

TEST(GapClosing, AGapOfExactlyOneCellIsNotNarrower) {
  Map map = default_arena(4.0, 2.0);
  // 1.95 - 1.9 is 0.04999999999999982 in floating point.
  map.obstacles = {box(1.0, 0.4, 1.5, 1.9), box(1.0, 1.95, 1.5, 2.0)};
  EXPECT_TRUE(find_narrow_gaps(map, GridShape::with_cell(4.0, 2.0, 0.05)).empty());
  EXPECT_EQ(find_narrow_gaps(map, GridShape::with_cell(4.0, 2.0, 0.051)).size(), 1u);
  map.obstacles.push_back(box(0.5, 0.05, 0.8, 0.3));  // 0.05 from the bottom wall
  EXPECT_TRUE(find_narrow_gaps(map, GridShape::with_cell(4.0, 2.0, 0.05)).empty());
}

TEST(GapClosing, StrictOptionRefusesNamingTheNarrowestGapAndACellThatWorks) {
  const Map map = two_gaps();
  FlowOptions o;
  o.strict_gaps = true;
  const std::string m = option_error(map, o);
  expect_has(m, "2 gaps between obstacles");
  expect_has(m, "flow.strict_gaps");
  expect_has(m, "the narrowest: obstacles[2] and obstacles[3], 0.012 m apart at (3.006, 0.7)");
  expect_has(m, "use a cell of 0.011 m or finer");
  // The advised cell keeps every gap open.
  const std::size_t at = m.find("use a cell of ") + 14;
  const double cell = std::stod(m.substr(at));
  EXPECT_TRUE(find_narrow_gaps(map, GridShape::with_cell(4.0, 2.0, cell)).empty());
}

TEST(GapClosing, TheAdvisedCellWorksOnAwkwardArenas) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> width(3.0, 40.0), gap(0.003, 0.3);
  for (int k = 0; k < 200; ++k) {
    Map map = default_arena(width(rng), width(rng));
    const double g = gap(rng);
    map.obstacles = {box(1.0, 1.0, 2.0, 2.0), box(2.0 + g, 1.0, 2.5, 2.0)};
    const double cell = cell_keeping_gaps_open(map, g);
    EXPECT_GT(cell, 0.8 * g) << map.width << " x " << map.height << ", gap " << g;
    EXPECT_LE(cell, g);
    const GridShape shape = GridShape::with_cell(map.width, map.height, cell);
    EXPECT_TRUE(find_narrow_gaps(map, shape).empty()) << cell << " for gap " << g;
  }
}

TEST(GapClosing, ClosingThatSealsTheFlowSaysSoAndNamesTheGap) {
  Map map = default_arena(4.0, 2.0);
  // The only passage across is a 0.03 m slit between two blocks, and a wider
  // one (0.04 m) elsewhere is closed too.
  // The slit holds the centres at y = 0.975 of 5 cm cells.
  map.obstacles = {box(1.0, 0.0, 1.5, 0.96), box(1.0, 0.99, 1.5, 2.0), box(2.5, 0.2, 3.0, 0.5),
                   box(3.04, 0.2, 3.5, 0.5)};
  const std::string m = option_error(map, FlowOptions{});
  expect_has(m, "closing the 2 gaps narrower than one cell (open in the map) seals every inlet");
  expect_has(m, "obstacles[0] and obstacles[1], 0.03 m apart");
  expect_has(m, "use a cell of 0.029 m or finer");
  // The cell at which air passes is checked: the slit stays open on its grid.
  expect_has(m, "at a cell of 0.029 m air passes");
  const GridShape fine = GridShape::with_cell(4.0, 2.0, 0.029);
  Grid<std::uint8_t> solid = rasterize_occupancy(map, fine);
  close_narrow_gaps(map, fine, solid.values);
  EXPECT_TRUE(inlet_reaches_outlet(rasterize_labels(map, solid)));
  // With a blocked map and no gap at all, the plain message.
  Map blocked = default_arena(4.0, 2.0);
  blocked.obstacles = {box(1.0, 0.0, 1.5, 2.0)};
  try {
    solve(blocked, FlowOptions{});
    ADD_FAILURE() << "solved a blocked map";
  } catch (const InputError& e) {
    expect_has(e.what(), "no free path from the inlet to the outlet");
  }
}

TEST(GapClosing, BucketSearchFindsWhatBruteForceFinds) {
  for (unsigned seed = 1; seed <= 20; ++seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> x(0.0, 6.0), y(0.0, 4.0), size(0.05, 0.6),
        angle(0.0, 6.283);
    Map map = default_arena(6.0, 4.0);
    for (int k = 0; k < 80; ++k) {
      const Vec2 c{x(rng), y(rng)};
      const double r = size(rng), t = angle(rng);
      Polygon p;  // a random triangle or quadrilateral around c
      const int n = 3 + static_cast<int>(seed % 2);
      for (int v = 0; v < n; ++v) {
        const double a = t + 6.283 * v / n;
        p.push_back({std::clamp(c.x + r * std::cos(a), 0.0, 6.0),
                     std::clamp(c.y + r * std::sin(a), 0.0, 4.0)});
      }
      map.obstacles.push_back(p);
    }
    const GridShape shape = GridShape::with_cell(6.0, 4.0, 0.05 + 0.01 * (seed % 5));
    const std::vector<GapReport> fast = find_narrow_gaps(map, shape);
    const std::vector<GapReport> slow = find_narrow_gaps_brute_force(map, shape);
    ASSERT_EQ(fast.size(), slow.size()) << "seed " << seed;
    ASSERT_FALSE(fast.empty()) << "seed " << seed;
    for (std::size_t k = 0; k < fast.size(); ++k) {
      EXPECT_EQ(fast[k].a, slow[k].a) << seed << " " << k;
      EXPECT_EQ(fast[k].b, slow[k].b) << seed << " " << k;
      EXPECT_EQ(fast[k].wall, slow[k].wall) << seed << " " << k;
      EXPECT_DOUBLE_EQ(fast[k].width, slow[k].width) << seed << " " << k;
    }
  }
}

TEST(DefaultCell, FiveCentimetresUpToBuildingScaleCoarserOnlyBeyond) {
  const FlowOptions automatic;
  EXPECT_EQ(automatic.cell, 0.0);
  EXPECT_EQ(resolved_cell(default_arena(), automatic), 0.05);      // 16 000 cells
  EXPECT_EQ(resolved_cell(19.2, 19.2, automatic), 0.05);           // tb3_world
  EXPECT_EQ(resolved_cell(30.2, 15.35, automatic), 0.05);          // depot
  EXPECT_EQ(resolved_cell(30.2, 50.2, automatic), 0.05);           // warehouse, 606 416 cells
  EXPECT_EQ(resolved_cell(40.0, 40.0, automatic), 0.05);           // 640 000 cells
  EXPECT_DOUBLE_EQ(resolved_cell(41.0, 41.0, automatic), 0.06);    // 466 489 cells
  EXPECT_DOUBLE_EQ(resolved_cell(100.0, 100.0, automatic), 0.15);  // 444 889 cells
  EXPECT_DOUBLE_EQ(resolved_cell(1000.0, 200.0, automatic), 0.6);  // 555 111 cells
  for (double side : {45.0, 80.0, 333.0, 2500.0}) {
    const double cell = resolved_cell(side, side * 0.7, automatic);
    const double cells = std::round(side / cell) * std::round(side * 0.7 / cell);
    EXPECT_LE(cells, kAutoCellMaxCells) << side;
    EXPECT_GT(cells, 0.4 * kAutoCellMaxCells) << side;  // not needlessly coarse
  }
  FlowOptions given;
  given.cell = 0.2;
  EXPECT_EQ(resolved_cell(100.0, 100.0, given), 0.2);
}

}  // namespace
}  // namespace plumekit::cfd
