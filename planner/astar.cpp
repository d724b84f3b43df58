#include "planner/astar.hpp"

#include <limits>
#include <queue>

namespace plumekit::planner {

namespace {

struct Entry {
  double f, g;
  int node, parent;
  bool checked;  // false: the segment from parent to node is not yet known free
};

struct Later {
  bool operator()(const Entry& a, const Entry& b) const {
    if (a.f != b.f) return a.f > b.f;
    return a.g < b.g;  // on ties, deeper first: reaches the goal sooner
  }
};

}  // namespace

Search shortest_path(const VisibilityGraph& graph, Vec2 start, Vec2 goal) {
  const FreeSpace& space = graph.free_space();
  const int n = graph.node_count();
  const int s = n, t = n + 1;
  auto pos = [&](int i) { return i < n ? graph.node(i) : i == s ? start : goal; };
  auto h = [&](int i) { return norm(goal - pos(i)); };

  std::vector<double> best(n + 2, std::numeric_limits<double>::infinity());
  std::vector<int> parent(n + 2, -1);
  std::vector<char> closed(n + 2, 0);
  std::vector<Entry> storage;
  storage.reserve(2 * n + 8);
  std::priority_queue<Entry, std::vector<Entry>, Later> open(Later(), std::move(storage));

  closed[s] = 1;
  best[s] = 0.0;
  // Lazy edges: an unchecked entry carries its exact cost, so it pops in
  // order and is checked only then; one that fails is dropped.
  open.push({h(s), h(s), t, s, false});
  for (int i = 0; i < n; ++i)
    if (graph.free_space().tangent_at(graph.vertex_of(i), start)) {
      const double g = norm(graph.node(i) - start);
      open.push({g + h(i), g, i, s, false});
    }

  Search out;
  while (!open.empty()) {
    const Entry e = open.top();
    open.pop();
    if (closed[e.node]) continue;
    if (e.checked) {
      if (e.g > best[e.node]) continue;  // superseded
    } else if (!space.segment_free(pos(e.parent), pos(e.node))) {
      continue;
    }
    closed[e.node] = 1;
    parent[e.node] = e.parent;
    ++out.expanded;
    if (e.node == t) {
      out.found = true;
      std::vector<Vec2> reversed;
      for (int k = t; k != -1; k = parent[k])
        reversed.push_back(pos(k));
      for (auto it = reversed.rbegin(); it != reversed.rend(); ++it)
        if (out.path.empty() || out.path.back() != *it) out.path.push_back(*it);
      if (out.path.size() == 1) out.path.push_back(goal);
      for (std::size_t k = 1; k < out.path.size(); ++k)
        out.length += norm(out.path[k] - out.path[k - 1]);
      return out;
    }
    const Vec2 p = pos(e.node);
    for (const VisibilityGraph::Arc& a : graph.arcs(e.node)) {
      if (closed[a.to]) continue;
      const double g = e.g + a.length;
      if (g < best[a.to]) {
        best[a.to] = g;
        open.push({g + h(a.to), g, a.to, e.node, true});
      }
    }
    if (space.tangent_at(graph.vertex_of(e.node), goal)) {
      const double g = e.g + norm(goal - p);
      open.push({g, g, t, e.node, false});
    }
  }
  return out;
}

}  // namespace plumekit::planner
