// The grid roadmap: travel distances over a floor, through doors, and none
// into a sealed room.
#include "planner/grid_roadmap.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "map/map.hpp"
#include "test_maps.hpp"

namespace plumekit::planner {
namespace {

using testing::two_rooms;

std::size_t nearest_node(const GridRoadmap& r, Vec2 p) {
  std::size_t best = 0;
  for (std::size_t k = 1; k < r.size(); ++k)
    if (norm(r.node(k) - p) < norm(r.node(best) - p)) best = k;
  return best;
}

TEST(GridRoadmap, OpenFloorDistancesAreWithinTheLatticeBoundOfStraightLines) {
  const FreeSpace space(default_arena(6.0, 4.0), 0.15, 8);
  const GridRoadmap roadmap(space, 0.25);
  ASSERT_GT(roadmap.size(), 300u);
  const Vec2 from{0.6, 0.7};
  const std::vector<double> d = roadmap.distances_from(from);
  for (std::size_t k = 0; k < roadmap.size(); ++k) {
    const double straight = norm(roadmap.node(k) - from);
    EXPECT_GE(d[k], straight - 1e-12);
    // Eight directions: at most 1 / cos(22.5 deg) of the straight line, plus the first hop.
    EXPECT_LE(d[k], 1.0824 * straight + 0.25 * std::sqrt(2.0)) << k;
  }
}

TEST(GridRoadmap, EachNodesPredecessorsWalkItsShortestWayBack) {
  const FreeSpace space(two_rooms(), 0.15, 8);
  const GridRoadmap roadmap(space, 0.25);
  const Vec2 from{2.0, 0.5};
  std::vector<int> previous;
  const std::vector<double> d = roadmap.distances_from(from, &previous);
  EXPECT_EQ(d, roadmap.distances_from(from));  // the same distances with the tree
  const std::size_t across = nearest_node(roadmap, {6.0, 0.5});
  // Back along the predecessors: each link adds its length, and the first node is reached
  // straight from `from`.
  double walked = 0.0;
  int k = static_cast<int>(across), hops = 0;
  bool through_door = false;
  while (previous[static_cast<std::size_t>(k)] >= 0) {
    const int p = previous[static_cast<std::size_t>(k)];
    walked +=
        norm(roadmap.node(static_cast<std::size_t>(k)) - roadmap.node(static_cast<std::size_t>(p)));
    through_door = through_door || roadmap.node(static_cast<std::size_t>(k)).y > 3.0;
    k = p;
    ++hops;
  }
  EXPECT_GT(hops, 10);
  EXPECT_TRUE(through_door);  // the wall's end is at y = 3 (test_maps.hpp)
  walked += norm(roadmap.node(static_cast<std::size_t>(k)) - from);
  EXPECT_NEAR(walked, d[across], 1e-9);
}

TEST(GridRoadmap, TheWayIntoTheNextRoomGoesThroughTheDoor) {
  const FreeSpace space(two_rooms(), 0.15, 8);
  const GridRoadmap roadmap(space, 0.25);
  const std::vector<double> d = roadmap.distances_from({2.0, 0.5});
  const std::size_t across = nearest_node(roadmap, {6.0, 0.5});
  // Straight across is 4 m. The shortest path rounds the wall's end, inflated by the 0.15 m
  // margin: up to (3.75, 3.15), across to (4.25, 3.15), down again.
  const double shortest = 2.0 * std::hypot(1.75, 2.65) + 0.5;
  EXPECT_GT(d[across], shortest - 1e-9);
  EXPECT_LT(d[across], 1.0824 * shortest + 0.25 * std::sqrt(2.0));
}

TEST(GridRoadmap, ASealedRoomIsUnreachable) {
  Map m = two_rooms();
  m.obstacles[0] = {{3.9, 0.0}, {4.1, 0.0}, {4.1, 4.0}, {3.9, 4.0}};  // no door
  const FreeSpace space(m, 0.15, 8);
  const GridRoadmap roadmap(space, 0.25);
  const std::vector<double> d = roadmap.distances_from({2.0, 2.0});
  for (std::size_t k = 0; k < roadmap.size(); ++k) {
    if (roadmap.node(k).x > 4.0)
      EXPECT_EQ(d[k], GridRoadmap::kUnreachable);
    else
      EXPECT_LT(d[k], 8.0);
  }
  EXPECT_THROW(GridRoadmap(space, 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace plumekit::planner
