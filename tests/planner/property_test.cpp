// Properties over seeded random maps: every path keeps the margin, every
// reachable goal is found, the VG path is the shortest (checked against a
// brute-force Dijkstra over all free-space vertices) and never longer than
// OMPL's.
#include <gtest/gtest.h>

#include <limits>
#include <memory>
#include <queue>

#include "core/error.hpp"
#include "planner/ompl_planner.hpp"
#include "planner/vg_planner.hpp"
#include "test_maps.hpp"

namespace plumekit::planner {
namespace {

using testing::clearance;
using testing::MapGenerator;

constexpr double kMargin = 0.15;

// Shortest path length by Dijkstra over every boundary vertex plus the two
// ends, every pair joined when the segment is free: no tangency pruning, no
// lazy checks, no A*.
class Reference {
 public:
  explicit Reference(const FreeSpace& space) : space_(space) {
    const std::size_t n = space.vertex_count();
    for (std::size_t i = 0; i < n; ++i)
      pts_.push_back(space.vertex(i));
    sees_.assign(n * n, 0);
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i + 1; j < n; ++j)
        sees_[i * n + j] = sees_[j * n + i] = space.segment_free(pts_[i], pts_[j]);
  }

  double shortest(Vec2 s, Vec2 g) const {
    const std::size_t n = pts_.size();
    std::vector<Vec2> p = pts_;
    p.push_back(s);
    p.push_back(g);
    auto sees = [&](std::size_t i, std::size_t j) {
      if (i < n && j < n) return sees_[i * n + j] != 0;
      return space_.segment_free(p[i], p[j]);
    };
    std::vector<double> d(n + 2, std::numeric_limits<double>::infinity());
    std::vector<char> done(n + 2, 0);
    d[n] = 0.0;
    for (;;) {
      std::size_t u = n + 2;
      for (std::size_t i = 0; i < n + 2; ++i)
        if (!done[i] && (u == n + 2 || d[i] < d[u])) u = i;
      if (u == n + 2 || d[u] == std::numeric_limits<double>::infinity()) break;
      done[u] = 1;
      if (u == n + 1) break;
      for (std::size_t v = 0; v < n + 2; ++v)
        if (!done[v] && d[u] + norm(p[v] - p[u]) < d[v] && sees(u, v))
          d[v] = d[u] + norm(p[v] - p[u]);
    }
    return d[n + 1];
  }

 private:
  const FreeSpace& space_;
  std::vector<Vec2> pts_;
  std::vector<char> sees_;
};

// An oracle independent of the planner's geometry: flood fill over 5 cm cells
// whose centres keep margin + 4 cm from every obstacle and wall (the half
// diagonal of a cell plus the N-gon's over-inflation is less), entered from the
// ends by straight segments that keep the margin. Connected means reachable.
class FloodFill {
 public:
  FloodFill(const Map& map, double margin)
      : map_(map),
        margin_(margin),
        nx_(static_cast<int>(map.width / kCell)),
        ny_(static_cast<int>(map.height / kCell)),
        ok_(nx_ * ny_) {
    for (int j = 0; j < ny_; ++j)
      for (int i = 0; i < nx_; ++i)
        ok_[j * nx_ + i] = clearance(map, {centre(i, j), centre(i, j)}) >= margin + 0.04;
  }

  bool connects(Vec2 s, Vec2 g) const {
    std::vector<char> seen(nx_ * ny_, 0);
    std::vector<int> stack = entries(s);
    for (int c : stack)
      seen[c] = 1;
    while (!stack.empty()) {
      const int c = stack.back();
      stack.pop_back();
      const int i = c % nx_, j = c / nx_;
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di) {
          const int a = i + di, b = j + dj;
          if (a < 0 || b < 0 || a >= nx_ || b >= ny_ || !ok_[b * nx_ + a] || seen[b * nx_ + a])
            continue;
          seen[b * nx_ + a] = 1;
          stack.push_back(b * nx_ + a);
        }
    }
    for (int c : entries(g))
      if (seen[c]) return true;
    return false;
  }

 private:
  static constexpr double kCell = 0.05;
  Vec2 centre(int i, int j) const { return {(i + 0.5) * kCell, (j + 0.5) * kCell}; }
  // Cells near p that a straight segment keeping the margin reaches.
  std::vector<int> entries(Vec2 p) const {
    std::vector<int> out;
    for (int j = 0; j < ny_; ++j)
      for (int i = 0; i < nx_; ++i)
        if (ok_[j * nx_ + i] && norm(centre(i, j) - p) < 0.15 &&
            clearance(map_, {p, centre(i, j)}) >= margin_)
          out.push_back(j * nx_ + i);
    return out;
  }

  const Map& map_;
  double margin_;
  int nx_, ny_;
  std::vector<char> ok_;
};

bool grid_connects(const Map& map, Vec2 s, Vec2 g, double margin) {
  return FloodFill(map, margin).connects(s, g);
}

// A query end: mostly random free points, sometimes exactly a free-space
// vertex or a point in the margin of a wall.
Vec2 pick(MapGenerator& gen, const Map& map, const FreeSpace& space, int mode) {
  if (mode == 0 && space.vertex_count() > 0)
    return space.vertex(gen.integer(0, static_cast<int>(space.vertex_count()) - 1));
  if (mode == 1) return {gen.lattice(0.0, 10.0), 0.05};
  return gen.free_point(map);
}

TEST(Property, RandomMapsKeepTheMarginFindEveryReachableGoalAndAreShortest) {
  MapGenerator gen(20210611);
  PlannerOptions options;
  options.margin = kMargin;
  int found = 0, unreachable = 0, moved = 0;
  const int maps = 1000, queries = 10;
  for (int m = 0; m < maps; ++m) {
    const Map map = gen.next();
    const VisibilityGraphPlanner vg(map, options);
    const FreeSpace& space = vg.free_space();
    const Reference reference(space);
    std::unique_ptr<FloodFill> flood;  // built for the first unreachable query only
    for (int q = 0; q < queries; ++q) {
      Vec2 s = pick(gen, map, space, q % 5), g = pick(gen, map, space, (q + 2) % 5);
      if (map.obstacle_at(s) >= 0 || map.obstacle_at(g) >= 0) continue;
      SCOPED_TRACE(::testing::Message() << "map " << m << " query " << q << " from " << to_string(s)
                                        << " to " << to_string(g));
      if (space.empty()) {
        EXPECT_THROW(vg.plan(s, g), InputError);
        continue;
      }
      const Vec2 s2 = space.nearest_free(s), g2 = space.nearest_free(g);
      ASSERT_TRUE(space.contains(s2));
      ASSERT_TRUE(space.contains(g2));
      const int rs = space.region_of(s2), rg = space.region_of(g2);
      ASSERT_GE(rs, 0);
      ASSERT_GE(rg, 0);
      const double best = reference.shortest(s2, g2);
      PlanResult r;
      try {
        r = vg.plan(s, g);
      } catch (const InputError& e) {
        ++unreachable;
        EXPECT_NE(rs, rg) << "a reachable goal was not found: " << e.what();
        EXPECT_EQ(best, std::numeric_limits<double>::infinity());
        if (!flood) flood = std::make_unique<FloodFill>(map, kMargin);
        EXPECT_FALSE(flood->connects(s2, g2)) << "a flood fill joins them";
        continue;
      }
      ++found;
      moved += r.start_moved + r.goal_moved;
      EXPECT_EQ(rs, rg);
      EXPECT_EQ(r.start, s2);
      EXPECT_EQ(r.goal, g2);
      ASSERT_GE(r.path.size(), 2u);
      EXPECT_EQ(r.path.front(), s2);
      EXPECT_EQ(r.path.back(), g2);
      double length = 0.0;
      for (std::size_t k = 1; k < r.path.size(); ++k) {
        EXPECT_TRUE(space.segment_free(r.path[k - 1], r.path[k]));
        length += norm(r.path[k] - r.path[k - 1]);
      }
      EXPECT_NEAR(r.length, length, 1e-9);
      EXPECT_NEAR(r.length, best, 1e-9);
      EXPECT_GE(clearance(map, r.path), kMargin - 1e-9);
    }
  }
  // The generator must exercise all the outcomes, or this test proves little.
  EXPECT_GT(found, 8000);
  EXPECT_GT(unreachable, 40);
  EXPECT_GT(moved, 1000);
  std::printf("[ property ] %d paths found, %d unreachable, %d ends moved\n", found, unreachable,
              moved);
}

TEST(Property, TheFloodFillOracleSeesGapsAndWalls) {
  using testing::map_with;
  using testing::rect;
  EXPECT_TRUE(grid_connects(map_with({}), {1, 2}, {9, 2}, kMargin));
  EXPECT_FALSE(grid_connects(map_with({rect(4, 0, 5, 4)}), {1, 2}, {9, 2}, kMargin));
  // A 0.45 m gap passes a 0.15 m margin; a 0.25 m gap does not.
  EXPECT_TRUE(
      grid_connects(map_with({rect(4, 0, 5, 1.8), rect(4, 2.25, 5, 4)}), {1, 2}, {9, 2}, kMargin));
  EXPECT_FALSE(
      grid_connects(map_with({rect(4, 0, 5, 1.8), rect(4, 2.05, 5, 4)}), {1, 2}, {9, 2}, kMargin));
}

TEST(Property, VgIsNeverLongerThanOmpl) {
  MapGenerator gen(7);
  PlannerOptions options;
  options.margin = kMargin;
  options.ompl_iterations = 1500;
  options.ompl_time_limit_s = 2.0;
  int compared = 0;
  for (int m = 0; m < 12; ++m) {
    const Map map = gen.next();
    const VisibilityGraphPlanner vg(map, options);
    const OmplPlanner rrt(map, options, PlannerKind::RRTstar);
    const OmplPlanner prm(map, options, PlannerKind::PRMstar);
    for (int q = 0; q < 2; ++q) {
      const Vec2 s = gen.free_point(map), g = gen.free_point(map);
      PlanResult best;
      try {
        best = vg.plan(s, g);
      } catch (const InputError&) {
        continue;  // unreachable: OMPL cannot find it either (below)
      }
      for (const OmplPlanner* p : {&rrt, &prm}) {
        SCOPED_TRACE(::testing::Message() << to_string(p->kind()) << " map " << m << " from "
                                          << to_string(s) << " to " << to_string(g));
        try {
          const PlanResult r = p->plan(s, g);
          ++compared;
          EXPECT_LE(best.length, r.length + 1e-9);
          EXPECT_GE(clearance(map, r.path), kMargin - 1e-9);
          EXPECT_EQ(r.path.front(), best.start);
          EXPECT_EQ(r.path.back(), best.goal);
        } catch (const InputError&) {
          // Not found within the budget: allowed for a sampling planner.
        }
      }
    }
  }
  EXPECT_GT(compared, 20);
}

TEST(Property, OmplStopsOnceItsPathMeetsTheTargetLength) {
  const Map m = testing::map_with({{{4.0, 1.0},
                                    {5.8, 1.0},
                                    {5.8, 3.0},
                                    {4.0, 3.0},
                                    {4.0, 2.6},
                                    {5.3, 2.6},
                                    {5.3, 1.4},
                                    {4.0, 1.4}},
                                   testing::rect(7.5, 0, 8.1, 1.2)});
  PlannerOptions options;
  const double best = VisibilityGraphPlanner(m, options).plan({4.6, 2}, {9, 2}).length;
  options.ompl_iterations = 1000000;
  options.ompl_time_limit_s = 600.0;
  options.ompl_target_length = 1.5 * best;
  options.ompl_simplify = false;
  for (PlannerKind kind : {PlannerKind::RRTstar, PlannerKind::PRMstar}) {
    const PlanResult r = OmplPlanner(m, options, kind).plan({4.6, 2}, {9, 2});
    EXPECT_LE(r.length, 1.5 * best + 1e-9) << to_string(kind);
    EXPECT_GE(r.length, best - 1e-9) << to_string(kind);
    EXPECT_LT(r.expanded, 1000000) << to_string(kind);
  }
}

TEST(Property, OmplFailsCleanlyOnAnUnreachableGoal) {
  PlannerOptions options;
  options.ompl_iterations = 300;
  const Map wall = testing::map_with({testing::rect(4, 0, 5, 4)});
  EXPECT_THROW(OmplPlanner(wall, options, PlannerKind::RRTstar).plan({1, 2}, {9, 2}), InputError);
  EXPECT_THROW(OmplPlanner(wall, options, PlannerKind::PRMstar).plan({1, 2}, {9, 2}), InputError);
  EXPECT_THROW(OmplPlanner(wall, options, PlannerKind::RRTstar).plan({4.5, 2}, {9, 2}), InputError);
}

}  // namespace
}  // namespace plumekit::planner
