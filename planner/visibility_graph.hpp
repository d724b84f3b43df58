#pragma once
// The visibility graph of the inflated free space: its nodes are the convex
// corners of the inflated obstacles, its edges the segments between them that
// stay in free space. Built once per map; queries (astar.hpp) link the start
// and goal to it without rebuilding.
#include <vector>

#include "planner/free_space.hpp"

namespace plumekit::planner {

class VisibilityGraph {
 public:
  struct Arc {
    int to;
    double length;
  };

  // Keeps a reference: `free_space` must outlive the graph.
  explicit VisibilityGraph(const FreeSpace& free_space);

  const FreeSpace& free_space() const { return free_space_; }
  int node_count() const { return static_cast<int>(nodes_.size()); }
  Vec2 node(int i) const { return nodes_[i]; }
  // The node's index among free_space().vertex().
  std::size_t vertex_of(int i) const { return vertex_[i]; }
  const std::vector<Arc>& arcs(int i) const { return arcs_[i]; }
  std::size_t edge_count() const { return edges_; }

 private:
  const FreeSpace& free_space_;
  std::vector<Vec2> nodes_;
  std::vector<std::size_t> vertex_;
  std::vector<std::vector<Arc>> arcs_;
  std::size_t edges_ = 0;
};

}  // namespace plumekit::planner
