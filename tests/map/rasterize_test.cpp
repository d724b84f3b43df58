#include "map/rasterize.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace plumekit {
namespace {

Map arena_with(std::vector<Polygon> obstacles) {
  Map map = default_arena(10.0, 4.0);
  map.obstacles = std::move(obstacles);
  return map;
}

TEST(Rasterize, GridShapeRoundsToWholeCells) {
  const GridShape s = GridShape::with_cell(10.0, 4.0, 0.05);
  EXPECT_EQ(s.nx, 200);
  EXPECT_EQ(s.ny, 80);
  EXPECT_DOUBLE_EQ(s.dx(), 0.05);
  const GridShape odd = GridShape::with_cell(10.0, 4.0, 0.3);  // 33.3 -> 33 cells
  EXPECT_EQ(odd.nx, 33);
  EXPECT_NEAR(odd.dx() * odd.nx, 10.0, 1e-12);
  EXPECT_EQ(odd.ny, 13);
  const GridShape s64{64, 64, 10.0, 4.0};  // the CNN's grid: non-square cells
  EXPECT_DOUBLE_EQ(s64.centre(0, 63).y, 4.0 - 0.5 * 4.0 / 64);
}

// rasterize_occupancy consults only the edges near each row; the answer must
// be covers() at every centre, bit for bit, on stair-step outlines whose edges
// and vertices lie on the cell centres, and on slanted ones.
TEST(Rasterize, RowFilteredOccupancyIsCoversAtEveryCentre) {
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> step(-3, 3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Map map = default_arena(10.0, 4.0);
  for (int k = 0; k < 12; ++k) {
    Polygon p;  // a staircase on the 0.025 m lattice (cell centres and faces of 5 cm cells)
    double x = 0.025 * std::round((0.5 + 8.5 * u(rng)) / 0.025),
           y = 0.025 * std::round((0.3 + 3.0 * u(rng)) / 0.025);
    for (int v = 0; v < 8; ++v) {
      p.push_back({x, y});
      (v % 2 ? y : x) += 0.025 * (step(rng) == 0 ? 1 : step(rng));
    }
    if (k % 3 == 0)
      for (Vec2& q : p)
        q = {q.x + 0.013 * q.y, q.y + 0.007 * q.x};  // slanted edges
    map.obstacles.push_back(p);
  }
  for (double cell : {0.05, 0.025, 0.07}) {
    const GridShape shape = GridShape::with_cell(10.0, 4.0, cell);
    const Grid<std::uint8_t> grid = rasterize_occupancy(map, shape);
    for (int j = 0; j < shape.ny; ++j)
      for (int i = 0; i < shape.nx; ++i) {
        bool solid = false;
        for (const Polygon& p : map.obstacles)
          solid = solid || covers(p, shape.centre(i, j));
        ASSERT_EQ(grid(i, j) != 0, solid) << cell << " at " << i << ", " << j;
      }
  }
}

TEST(Rasterize, CellIsSolidWhenItsCentreIsInsideOrOnTheBoundary) {
  // Cells of 1 m: centres at 0.5, 1.5, ... The square's edges pass through
  // the centres at x = 2.5 and y = 1.5 and between centres elsewhere.
  const Map map = arena_with({{{2.5, 0.2}, {4.2, 0.2}, {4.2, 1.5}, {2.5, 1.5}}});
  const auto g = rasterize_occupancy(map, GridShape{10, 4, 10.0, 4.0});
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 10; ++i) {
      const bool expected = (i == 2 || i == 3) && (j == 0 || j == 1);
      EXPECT_EQ(g(i, j), expected ? 1 : 0) << "cell " << i << "," << j;
    }
}

TEST(Rasterize, SolidAreaConvergesToPolygonArea) {
  const Polygon tri{{1.0, 0.3}, {6.1, 0.7}, {3.3, 3.6}};
  const Map map = arena_with({tri});
  double previous_error = HUGE_VAL;
  for (double cell : {0.2, 0.1, 0.05, 0.025}) {
    const GridShape s = GridShape::with_cell(10, 4, cell);
    const auto g = rasterize_occupancy(map, s);
    double area = 0;
    for (auto v : g.values)
      area += v * s.dx() * s.dy();
    const double error = std::abs(area - std::abs(signed_area(tri)));
    EXPECT_LT(error, previous_error) << "cell " << cell;
    EXPECT_LT(error, 20 * cell) << "cell " << cell;  // O(perimeter * cell)
    previous_error = error;
  }
}

TEST(Rasterize, LabelsMarkObstaclesWallsAndOpenings) {
  Map map = arena_with({{{4, 1}, {6, 1}, {6, 3}, {4, 3}}});
  // The inlet on the middle of the left wall only.
  map.openings[0] = wall_opening(map, Side::Left, 1.0, 3.0, OpeningKind::Inlet);
  const GridShape s{10, 4, 10.0, 4.0};
  const auto l = rasterize_labels(map, s);
  EXPECT_EQ(l(4, 1), kObstacle);
  EXPECT_EQ(l(5, 2), kObstacle);
  EXPECT_EQ(l(2, 2), kFree);
  EXPECT_EQ(l(0, 1), kInlet);  // centre y = 1.5 in [1, 3]
  EXPECT_EQ(l(0, 2), kInlet);
  EXPECT_EQ(l(0, 0), kWall);  // left-bottom corner, outside the inlet span
  EXPECT_EQ(l(0, 3), kWall);
  EXPECT_EQ(l(9, 0), kOutlet);  // corner cell: the outlet wins over the bottom wall
  EXPECT_EQ(l(9, 2), kOutlet);
  EXPECT_EQ(l(5, 0), kWall);
  EXPECT_EQ(l(5, 3), kWall);
}

TEST(Rasterize, ObstacleOnWallHidesTheWallLabel) {
  const Map map = arena_with({{{0, 0}, {2, 0}, {2, 1}, {0, 1}}});
  const auto l = rasterize_labels(map, GridShape{10, 4, 10.0, 4.0});
  EXPECT_EQ(l(0, 0), kObstacle);
  EXPECT_EQ(l(1, 0), kObstacle);
  EXPECT_EQ(l(0, 1), kInlet);
}

}  // namespace
}  // namespace plumekit

namespace plumekit {
namespace {

TEST(Rasterize, InletReachesOutletUnlessAWallBlocksTheWay) {
  const GridShape s = GridShape::with_cell(10, 4, 0.1);
  const Map open = arena_with({{{4, 0}, {5, 0}, {5, 3.5}, {4, 3.5}}});
  EXPECT_TRUE(inlet_reaches_outlet(rasterize_labels(open, s)));
  const Map closed = arena_with({{{4, 0}, {5, 0}, {5, 4}, {4, 4}}});
  EXPECT_FALSE(inlet_reaches_outlet(rasterize_labels(closed, s)));
  // A gap narrower than one cell closes the way at that resolution.
  const Map slit = arena_with({{{4, 0}, {5, 0}, {5, 3.96}, {4, 3.96}}});
  EXPECT_FALSE(inlet_reaches_outlet(rasterize_labels(slit, s)));
  EXPECT_TRUE(inlet_reaches_outlet(rasterize_labels(slit, GridShape::with_cell(10, 4, 0.02))));
}

}  // namespace
}  // namespace plumekit
