// The planner on hand-built maps: inflation, exact shortest paths, and the
// degenerate cases that public visibility-graph libraries get wrong.
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.hpp"
#include "planner/inflation.hpp"
#include "planner/planner.hpp"
#include "planner/vg_planner.hpp"
#include "test_maps.hpp"

namespace plumekit::planner {
namespace {

using testing::clearance;
using testing::map_with;
using testing::rect;

PlannerOptions square(double margin) {
  // A square "disk" (N = 4): inflated rectangles stay rectangles, so
  // shortest-path lengths can be written down by hand.
  PlannerOptions o;
  o.margin = margin;
  o.arc_segments = 4;
  return o;
}

double len(Vec2 a, Vec2 b) {
  return norm(b - a);
}

// The U-shape of data/maps/cluttered-2.json, open towards the left.
const Polygon kU = {{4.0, 1.0}, {5.8, 1.0}, {5.8, 3.0}, {4.0, 3.0},
                    {4.0, 2.6}, {5.3, 2.6}, {5.3, 1.4}, {4.0, 1.4}};

// ---- inflation -------------------------------------------------------------

TEST(Inflation, NgonCircumscribesTheDiskWithTheDocumentedBound) {
  for (int n : {4, 8, 12, 16, 32}) {
    const double r = 0.15;
    const Polygon g = circumscribed_ngon(r, n);
    ASSERT_EQ(g.size(), static_cast<std::size_t>(n));
    EXPECT_GT(signed_area(g), 0.0);
    double farthest = 0.0;
    for (int k = 0; k < n; ++k) {
      // Every edge is tangent to the circle: the disk lies inside.
      EXPECT_NEAR(distance_to_segment({0, 0}, g[k], g[(k + 1) % n]), r, 1e-15) << n;
      farthest = std::max(farthest, norm(g[k]));
    }
    EXPECT_NEAR(farthest - r, inflation_error_bound(r, n), 1e-15) << n;
    // Axis-facing edges lie exactly on x = +-r and y = +-r.
    int on_axes = 0;
    for (Vec2 v : g)
      on_axes += (std::abs(v.x) == r) + (std::abs(v.y) == r);
    EXPECT_EQ(on_axes, 8) << n;
  }
  EXPECT_NEAR(inflation_error_bound(0.15, 16), 0.15 * (1 / std::cos(M_PI / 16) - 1), 1e-18);
  EXPECT_LT(inflation_error_bound(0.15, 16), 0.003);
}

TEST(Inflation, ShrinksTheArenaAndGrowsARectangleExactly) {
  const auto regions = inflate_free_space(map_with({rect(4, 1, 5, 3)}), 0.25, 4);
  ASSERT_EQ(regions.size(), 1u);
  EXPECT_DOUBLE_EQ(signed_area(regions[0].outer), 9.5 * 3.5);
  ASSERT_EQ(regions[0].holes.size(), 1u);
  const Polygon& hole = regions[0].holes[0];
  EXPECT_LT(signed_area(hole), 0.0);  // clockwise: free space on the left
  const Box b = bounding_box(hole);
  EXPECT_EQ(b.lo.x, 3.75);
  EXPECT_EQ(b.lo.y, 0.75);
  EXPECT_EQ(b.hi.x, 5.25);
  EXPECT_EQ(b.hi.y, 3.25);
}

TEST(Inflation, MergesOverlappingAndTouchingObstacles) {
  // Overlapping, touching along an edge, and 0.2 m apart (less than 2 margins).
  const Map m = map_with(
      {rect(2, 1, 3, 2), rect(2.5, 1.5, 3.5, 2.5), rect(3.5, 1, 4, 2), rect(4.2, 1, 5, 2)});
  const auto regions = inflate_free_space(m, 0.15, 16);
  ASSERT_EQ(regions.size(), 1u);
  EXPECT_EQ(regions[0].holes.size(), 1u);
}

TEST(Inflation, ObstacleAgainstAWallLeavesNoHole) {
  const auto regions = inflate_free_space(map_with({rect(4, 0, 5, 2)}), 0.15, 16);
  ASSERT_EQ(regions.size(), 1u);
  EXPECT_TRUE(regions[0].holes.empty());
}

TEST(Inflation, EnclosedPocketIsItsOwnRegion) {
  // Four walls of a box: the free pocket inside is a separate region.
  const Map m =
      map_with({rect(3, 1, 6, 1.2), rect(3, 2.8, 6, 3), rect(3, 1, 3.2, 3), rect(5.8, 1, 6, 3)});
  const auto regions = inflate_free_space(m, 0.15, 16);
  EXPECT_EQ(regions.size(), 2u);
}

TEST(Inflation, NothingLeftWhenTheArenaIsTooNarrowOrFull) {
  EXPECT_TRUE(inflate_free_space(map_with({}), 2.0, 16).empty());
  EXPECT_TRUE(inflate_free_space(map_with({rect(0, 0, 10, 4)}), 0.15, 16).empty());
  EXPECT_FALSE(inflate_free_space(map_with({}), 1.9, 16).empty());
  EXPECT_THROW(inflate_free_space(map_with({}), -0.1, 16), InputError);
  EXPECT_THROW(inflate_free_space(map_with({}), 0.1, 3), InputError);
}

// ---- optimality ------------------------------------------------------------

TEST(Optimality, StraightLineInAnEmptyArena) {
  const auto p = make_planner(map_with({}));
  const PlanResult r = p->plan({1.0, 1.0}, {9.0, 3.5});
  ASSERT_EQ(r.path.size(), 2u);
  EXPECT_NEAR(r.length, len({1, 1}, {9, 3.5}), 1e-12);
  EXPECT_FALSE(r.start_moved);
  EXPECT_FALSE(r.goal_moved);
}

TEST(Optimality, OverAWallWithoutMargin) {
  const auto p = make_planner(map_with({rect(4, 0, 5, 3)}), square(0.0));
  const PlanResult r = p->plan({2, 1}, {8, 1});
  EXPECT_NEAR(r.length, len({2, 1}, {4, 3}) + 1.0 + len({5, 3}, {8, 1}), 1e-9);
  ASSERT_EQ(r.path.size(), 4u);
  EXPECT_EQ(r.path[1], (Vec2{4, 3}));
  EXPECT_EQ(r.path[2], (Vec2{5, 3}));
}

TEST(Optimality, OutOfAUShapeWithoutMargin) {
  const auto p = make_planner(map_with({kU}), square(0.0));
  const PlanResult r = p->plan({4.6, 2.0}, {7.0, 2.0});
  // Out past an arm's tip, along the arm's end and the U's side, then across:
  // path segments that run along obstacle edges, through collinear vertices.
  EXPECT_NEAR(r.length, len({4.6, 2}, {4, 1.4}) + 0.4 + 1.8 + len({5.8, 1}, {7, 2}), 1e-9);
}

TEST(Optimality, OutOfAUShapeWithMargin) {
  const auto p = make_planner(map_with({kU}), square(0.1));
  const PlanResult r = p->plan({4.6, 2.0}, {7.0, 2.0});
  EXPECT_NEAR(r.length, len({4.6, 2}, {3.9, 1.5}) + 0.6 + 2.0 + len({5.9, 0.9}, {7, 2}), 1e-9);
  EXPECT_GE(clearance(map_with({kU}), r.path), 0.1 - 1e-9);
}

TEST(Optimality, ThroughAGap) {
  // A wall across the arena with a 0.4 m gap at y in [1.8, 2.2].
  const Map m = map_with({rect(4, 0, 5, 1.8), rect(4, 2.2, 5, 4)});
  const auto p = make_planner(m, square(0.1));
  const PlanResult r = p->plan({1, 1}, {9, 3});
  EXPECT_NEAR(r.length,
              len({1, 1}, {3.9, 1.9}) + len({3.9, 1.9}, {5.1, 2.1}) + len({5.1, 2.1}, {9, 3}),
              1e-9);
  EXPECT_GE(clearance(m, r.path), 0.1 - 1e-9);
}

TEST(Optimality, DefaultInflationAroundTheU) {
  // N = 16: the path bends round the arc vertices; its length is bounded by
  // the exact-disk optimum (below) and the N = 4 optimum (above).
  const Map m = map_with({kU});
  const auto p = make_planner(m);
  const PlanResult r = p->plan({4.6, 2.0}, {7.0, 2.0});
  EXPECT_GE(clearance(m, r.path), 0.15 - 1e-9);
  const double square_len = make_planner(m, square(0.15))->plan({4.6, 2.0}, {7.0, 2.0}).length;
  EXPECT_LT(r.length, square_len);
  EXPECT_GT(r.length, make_planner(m, square(0.0))->plan({4.6, 2.0}, {7.0, 2.0}).length);
}

// ---- degenerate cases --------------------------------------------------------

TEST(Degenerate, PathGrazesCollinearVertices) {
  // Three blocks with collinear tops (one with extra vertices on its edges):
  // the straight line along y = 1 touches them all and stays free.
  const Map m = map_with(
      {rect(2, 0, 3, 1), {{5, 0}, {5.5, 0}, {6, 0}, {6, 1}, {5.5, 1}, {5, 1}}, rect(8, 0, 9, 1)});
  const auto p = make_planner(m, square(0.0));
  const PlanResult r = p->plan({1, 1}, {9.5, 1});
  EXPECT_EQ(r.path.size(), 2u);
  EXPECT_NEAR(r.length, 8.5, 1e-12);
  // The same line 1 mm lower cuts the blocks: the path must go over them.
  const PlanResult low = p->plan({1, 0.999}, {9.5, 0.999});
  EXPECT_GT(low.length, 8.5);
}

TEST(Degenerate, StartAndGoalOnTheInflatedBoundaryAndAtVertices) {
  // Rectangle [4,5]x[1,3] grown by 0.25 (exact in binary) to [3.75,5.25]x[0.75,3.25].
  const auto p = make_planner(map_with({rect(4, 1, 5, 3)}), square(0.25));
  const PlanResult on_edge = p->plan({3.75, 2.0}, {5.25, 3.25});
  EXPECT_FALSE(on_edge.start_moved);
  EXPECT_FALSE(on_edge.goal_moved);
  EXPECT_NEAR(on_edge.length, 1.25 + 1.5, 1e-12);  // up the side, along the top
  const PlanResult corners = p->plan({3.75, 0.75}, {5.25, 3.25});
  EXPECT_NEAR(corners.length, 4.0, 1e-12);
  const PlanResult same_edge = p->plan({3.75, 1.0}, {3.75, 3.0});
  EXPECT_EQ(same_edge.path.size(), 2u);
  EXPECT_NEAR(same_edge.length, 2.0, 1e-12);
  // On the shrunk arena's boundary too.
  const PlanResult walls = p->plan({0.25, 0.25}, {9.75, 0.25});
  EXPECT_NEAR(walls.length, 9.5, 1e-12);
}

TEST(Degenerate, StartInsideTheMarginMovesToTheNearestFreePoint) {
  const auto p = make_planner(map_with({rect(4, 1, 5, 3)}), square(0.25));
  const PlanResult r = p->plan({3.9, 2.0}, {0.1, 2.0});
  EXPECT_TRUE(r.start_moved);
  EXPECT_TRUE(r.goal_moved);
  EXPECT_EQ(r.requested_start, (Vec2{3.9, 2.0}));
  EXPECT_EQ(r.start, (Vec2{3.75, 2.0}));
  EXPECT_EQ(r.goal, (Vec2{0.25, 2.0}));
  EXPECT_EQ(r.path.front(), r.start);
  EXPECT_NEAR(r.length, 3.5, 1e-12);
  // A point in the margin of a slanted edge lands exactly in free space.
  const Map slanted = map_with({{{4, 1}, {6, 1.7}, {4.5, 3}}});
  const auto q = make_planner(slanted);
  const PlanResult s = q->plan({5.0, 1.2}, {9, 1});
  EXPECT_TRUE(s.start_moved);
  EXPECT_GE(clearance(slanted, s.path), 0.15 - 1e-9);
  EXPECT_LT(norm(s.start - Vec2{5.0, 1.2}), 0.2);
}

TEST(Degenerate, ObstaclesTouchingEachOtherAndAWall) {
  // An L built from two rectangles that share an edge, the upright on the floor.
  const Map m = map_with({rect(3, 0, 4, 2), rect(4, 1.5, 6, 2)});
  const auto p = make_planner(m, square(0.0));
  const PlanResult r = p->plan({5, 0.5}, {1, 1});
  EXPECT_NEAR(r.length, len({5, 0.5}, {6, 1.5}) + 0.5 + 3.0 + len({3, 2}, {1, 1}), 1e-9);
  const auto q = make_planner(m);
  EXPECT_GE(clearance(m, q->plan({5, 0.5}, {1, 1}).path), 0.15 - 1e-9);
}

TEST(Degenerate, CornersTouchingAtAPointLetAPathThrough) {
  // Two squares meeting at the corner (3, 2): free space pinches to a point
  // there, and the closed free space holds that point.
  const auto p = make_planner(map_with({rect(2, 1, 3, 2), rect(3, 2, 4, 3)}), square(0.0));
  const PlanResult r = p->plan({2.5, 2.5}, {3.5, 1.5});
  EXPECT_EQ(r.path.size(), 2u);
  EXPECT_NEAR(r.length, std::sqrt(2.0), 1e-12);
  // Across the pinch the other way is through both squares.
  const PlanResult around = p->plan({2.0, 0.5}, {4.0, 3.5});
  EXPECT_GT(around.length, len({2, 0.5}, {4, 3.5}) + 1e-3);
}

TEST(Degenerate, GapOfExactlyTwiceTheMarginIsClosed) {
  // Inflated by 0.25, the two wall pieces meet along y = 2: the merged
  // (regularized) obstacle leaves no zero-width passage.
  const Map closed = map_with({rect(4, 0, 5, 1.75), rect(4, 2.25, 5, 4)});
  EXPECT_THROW(make_planner(closed, square(0.25))->plan({1, 2}, {9, 2}), InputError);
  const Map open = map_with({rect(4, 0, 5, 1.75), rect(4, 2.2500001, 5, 4)});
  const PlanResult r = make_planner(open, square(0.25))->plan({1, 2}, {9, 2});
  EXPECT_GE(clearance(open, r.path), 0.25 - 1e-9);
}

TEST(Degenerate, SliverThinnerThanAnUlpIsCut) {
  // Found by the property test: 9.7 + 0.15 rounds just below the shrunk wall at
  // 9.85, leaving a free sliver 1e-15 m wide that rounds to a spike in the
  // boundary. The path must not run up the wall through the other obstacle.
  const Map m = map_with({{{9.8500000000000014, 2.35},
                           {9.25, 2.35},
                           {9.25, 1.6},
                           {8.55, 1.6},
                           {8.55, 1},
                           {9.8500000000000014, 1}},
                          {{9.2, 0.75},
                           {9.7, 0.75},
                           {9.7, 0.9},
                           {9.35, 0.9},
                           {9.35, 2.4},
                           {9.7, 2.4},
                           {9.7, 2.55},
                           {9.2, 2.55}}});
  const PlanResult r = make_planner(m)->plan({9.6, 0.05}, {9.904, 3.437});
  EXPECT_GE(clearance(m, r.path), 0.15 - 1e-9);
  EXPECT_GT(r.length, 4.0);
}

TEST(Degenerate, GoalInsideAnObstacleIsAnError) {
  const auto p = make_planner(map_with({rect(4, 1, 5, 3)}));
  try {
    p->plan({1, 1}, {4.5, 2});
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("goal (4.5, 2) lies inside obstacles[0]"),
              std::string::npos)
        << e.what();
  }
  EXPECT_THROW(p->plan({4, 2}, {1, 1}), InputError);   // on the obstacle's boundary
  EXPECT_THROW(p->plan({-1, 2}, {1, 1}), InputError);  // outside the arena
  EXPECT_THROW(p->plan({1, 1}, {NAN, 1}), InputError);
}

TEST(Degenerate, FullyBlockedMapIsAnError) {
  const auto wall = make_planner(map_with({rect(4, 0, 5, 4)}));
  try {
    wall->plan({1, 2}, {9, 2});
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("cannot be reached"), std::string::npos) << e.what();
  }
  PlannerOptions wide;
  wide.margin = 2.5;
  EXPECT_THROW(make_planner(map_with({}), wide)->plan({1, 2}, {9, 2}), InputError);
  // A goal in an enclosed pocket.
  const Map box =
      map_with({rect(3, 1, 6, 1.2), rect(3, 2.8, 6, 3), rect(3, 1, 3.2, 3), rect(5.8, 1, 6, 3)});
  EXPECT_THROW(make_planner(box)->plan({1, 2}, {4.5, 2}), InputError);
  EXPECT_NO_THROW(make_planner(box)->plan({4, 2}, {5, 2}));
}

TEST(Degenerate, StartEqualsGoal) {
  const auto p = make_planner(map_with({rect(4, 1, 5, 3)}));
  const PlanResult r = p->plan({2, 2}, {2, 2});
  EXPECT_EQ(r.path.size(), 2u);
  EXPECT_EQ(r.length, 0.0);
}

TEST(Planner, ParsesKinds) {
  EXPECT_EQ(parse_planner_kind("vg"), PlannerKind::VisibilityGraph);
  EXPECT_EQ(parse_planner_kind("rrtstar"), PlannerKind::RRTstar);
  EXPECT_EQ(parse_planner_kind("prmstar"), PlannerKind::PRMstar);
  try {
    parse_planner_kind("astar");
    ADD_FAILURE() << "no OptionError";
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "planner.kind");  // the CLI shows its flag, --planner
    EXPECT_NE(e.message().find("unknown planner 'astar'"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace plumekit::planner
