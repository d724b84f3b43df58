// Thin walls (cfd/thin_walls.hpp): obstacles the flow grid lets air through.
#include "cfd/thin_walls.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "cfd/flow_solver.hpp"
#include "cfd/gap_closing.hpp"
#include "map/rasterize.hpp"

namespace plumekit::cfd {
namespace {

Polygon box(double x0, double y0, double x1, double y1) {
  return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
}

// A 10 x 4 m arena with a 4 cm wall across most of its height, x in [5.06, 5.10]:
// 10 cm cells have centres at x = 5.05 and 5.15, none in the wall; 5 cm cells
// have one at 5.075.
Map thin_wall_map() {
  Map map = default_arena(10.0, 4.0);
  map.obstacles = {box(5.06, 0.0, 5.10, 3.0), box(1.0, 1.0, 2.0, 2.0)};
  return map;
}

std::vector<ThinWall> walls_at(const Map& map, double cell) {
  const GridShape shape = GridShape::with_cell(map.width, map.height, cell);
  Grid<std::uint8_t> solid = rasterize_occupancy(map, shape);
  close_narrow_gaps(map, shape, solid.values);
  return find_thin_walls(map, shape, solid.values);
}

TEST(ThinWalls, AWallWithNoCellCentreInItIsFoundWithItsThicknessAndPlace) {
  const Map map = thin_wall_map();
  const std::vector<ThinWall> walls = walls_at(map, 0.1);
  ASSERT_EQ(walls.size(), 1u);
  EXPECT_EQ(walls[0].obstacle, 0);
  EXPECT_EQ(walls[0].leaks, 30);  // the rows of centres y = 0.05 ... 2.95
  EXPECT_NEAR(walls[0].thickness, 0.04, 1e-12);
  EXPECT_NEAR(walls[0].at.x, 5.1, 1e-12);  // between the centres 5.05 and 5.15
  EXPECT_GT(walls[0].at.y, 0.0);
  EXPECT_LT(walls[0].at.y, 3.0);
  const ThinWalls summary = summarize_thin_walls(map, walls);
  EXPECT_NEAR(summary.resolving_cell, 0.04, 1e-12);
  const std::string text = thin_walls_text(summary, 0.1);
  EXPECT_NE(text.find("the 0.1 m cells do not resolve 1 obstacle, so air flows through it"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("obstacles[0] at (5.1, "), std::string::npos) << text;
  EXPECT_NE(text.find("0.04 m thick (30 cell faces through it)"), std::string::npos) << text;
  EXPECT_NE(text.find("a cell of 0.04 m or finer resolves it"), std::string::npos) << text;
  // The finer grid puts cells in it, and so does the cell the report advises.
  EXPECT_TRUE(walls_at(map, 0.05).empty());
  EXPECT_TRUE(walls_at(map, summary.resolving_cell).empty());
}

TEST(ThinWalls, AFramedMapReportsTheWallInTheMapFrame) {
  Map map = thin_wall_map();
  map.frame.origin = {100.0, -20.0};
  const ThinWalls summary = summarize_thin_walls(map, walls_at(map, 0.1));
  ASSERT_EQ(summary.walls.size(), 1u);
  EXPECT_NEAR(summary.walls[0].at.x, 105.1, 1e-9);
  EXPECT_LT(summary.walls[0].at.y, -17.0);
}

// Every pair of 4-neighbouring free cells, its segment sampled finely: the
// obstacles whose interior it enters, and how many pairs each.
std::vector<std::pair<int, int>> brute_force(const Map& map, double cell) {
  const GridShape s = GridShape::with_cell(map.width, map.height, cell);
  Grid<std::uint8_t> solid = rasterize_occupancy(map, s);
  close_narrow_gaps(map, s, solid.values);
  std::vector<int> leaks(map.obstacles.size(), 0);
  for (int j = 0; j < s.ny; ++j)
    for (int i = 0; i < s.nx; ++i)
      for (const auto& [di, dj] : {std::pair{1, 0}, std::pair{0, 1}}) {
        if (!s.contains(i + di, j + dj) || solid(i, j) || solid(i + di, j + dj)) continue;
        const Vec2 a = s.centre(i, j), b = s.centre(i + di, j + dj);
        for (std::size_t k = 0; k < map.obstacles.size(); ++k) {
          bool near = false;  // the segment meets the obstacle's bounding box
          for (const Vec2 v : map.obstacles[k])
            near = near || (std::abs(v.x - a.x) < 2.0 && std::abs(v.y - a.y) < 2.0);
          bool in = false;
          for (int t = 1; t < 1500 && near && !in; ++t)
            in = locate(map.obstacles[k], a + (t / 1500.0) * (b - a)) == Location::Inside;
          leaks[k] += in;
        }
      }
  std::vector<std::pair<int, int>> out;
  for (std::size_t k = 0; k < leaks.size(); ++k)
    if (leaks[k] > 0) out.emplace_back(static_cast<int>(k), leaks[k]);
  return out;
}

TEST(ThinWalls, AgreesWithABruteForceSearchOnSlantedAndJaggedWalls) {
  Map map = default_arena(6.0, 4.0);
  map.obstacles = {
      {{1.0, 0.5}, {1.05, 0.5}, {2.05, 2.5}, {2.0, 2.5}},  // slanted, 5 cm
      {{3.0, 1.0},
       {4.5, 1.0},
       {4.5, 1.06},
       {3.4, 1.06},
       {3.4, 2.0},
       {3.3, 2.0},
       {3.3, 1.06},
       {3.0, 1.06}},                                       // a thin T
      box(4.8, 2.5, 5.6, 3.5),                             // thick
      {{0.5, 3.0}, {1.5, 3.2}, {1.5, 3.27}, {0.5, 3.07}},  // shallow slant
  };
  for (double cell : {0.1, 0.13, 0.2}) {
    std::vector<std::pair<int, int>> found;
    for (const ThinWall& w : walls_at(map, cell))
      found.emplace_back(w.obstacle, w.leaks);
    EXPECT_EQ(found, brute_force(map, cell)) << "cell " << cell;
    EXPECT_FALSE(found.empty()) << "cell " << cell;
  }
}

TEST(ThinWalls, TheFlowSummaryListsThem) {
  FlowOptions o;
  o.cell = 0.2;
  o.convection = Convection::Upwind;  // converges on this coarse grid
  Map map = default_arena(6.0, 3.0);
  map.obstacles = {box(3.02, 0.0, 3.08, 2.0)};  // centres at 2.9 and 3.1: none in it
  const FlowResult r = solve(map, o);
  ASSERT_EQ(r.summary.thin_walls.walls.size(), 1u);
  EXPECT_EQ(r.summary.thin_walls.walls[0].leaks, 10);
  o.cell = 0.05;
  EXPECT_TRUE(solve(map, o).summary.thin_walls.walls.empty());
}

}  // namespace
}  // namespace plumekit::cfd
