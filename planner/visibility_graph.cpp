#include "planner/visibility_graph.hpp"

namespace plumekit::planner {

VisibilityGraph::VisibilityGraph(const FreeSpace& free_space) : free_space_(free_space) {
  for (std::size_t v = 0; v < free_space.vertex_count(); ++v)
    if (free_space.is_bend_vertex(v)) {
      nodes_.push_back(free_space.vertex(v));
      vertex_.push_back(v);
    }
  const int n = node_count();
  arcs_.resize(n);
  // Only bitangent segments can be part of a shortest path (a path that bent
  // at a node where its line cuts into the obstacle could be shortened); the
  // tangency test is two orientations, so it runs before the visibility test.
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j) {
      if (!free_space.tangent_at(vertex_[i], nodes_[j]) ||
          !free_space.tangent_at(vertex_[j], nodes_[i]))
        continue;
      if (!free_space.segment_free(nodes_[i], nodes_[j])) continue;
      const double d = norm(nodes_[j] - nodes_[i]);
      arcs_[i].push_back({j, d});
      arcs_[j].push_back({i, d});
      ++edges_;
    }
}

}  // namespace plumekit::planner
