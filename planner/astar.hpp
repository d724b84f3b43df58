#pragma once
// A* over the visibility graph with the Euclidean heuristic, linking the start
// and goal for this query only.
#include <vector>

#include "planner/visibility_graph.hpp"

namespace plumekit::planner {

struct Search {
  bool found = false;
  std::vector<Vec2> path;  // start ... goal, no repeated consecutive points
  double length = 0.0;
  int expanded = 0;  // nodes closed
};

// The shortest path from `start` to `goal` in the graph's free space; both
// must lie in it. The start's and goal's segments are checked lazily (when
// A* pops them), so a query costs a few segment tests, not one per node.
Search shortest_path(const VisibilityGraph& graph, Vec2 start, Vec2 goal);

}  // namespace plumekit::planner
