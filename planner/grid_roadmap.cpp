#include "planner/grid_roadmap.hpp"

#include <cmath>
#include <functional>
#include <queue>
#include <stdexcept>

namespace plumekit::planner {

GridRoadmap::GridRoadmap(const FreeSpace& space, double spacing)
    : space_(space), spacing_(spacing) {
  if (!(spacing > 0.0)) throw std::invalid_argument("GridRoadmap: spacing must be > 0");
  const Map& map = space.map();
  nx_ = std::max(1, static_cast<int>(std::floor(map.width / spacing)));
  ny_ = std::max(1, static_cast<int>(std::floor(map.height / spacing)));
  // Centre the lattice in the arena, so that the leftover is split evenly.
  first_ = {0.5 * (map.width - nx_ * spacing) + 0.5 * spacing,
            0.5 * (map.height - ny_ * spacing) + 0.5 * spacing};
  node_of_.assign(static_cast<std::size_t>(nx_) * ny_, -1);
  for (int j = 0; j < ny_; ++j)
    for (int i = 0; i < nx_; ++i) {
      const Vec2 p{first_.x + i * spacing, first_.y + j * spacing};
      if (!space.contains(p)) continue;
      node_of_[j * nx_ + i] = static_cast<int>(nodes_.size());
      nodes_.push_back(p);
      cell_.push_back(j * nx_ + i);
    }
  // Each undirected link is tested once (towards the four "forward" neighbours).
  std::vector<std::vector<Link>> adjacent(nodes_.size());
  const int di[4] = {1, -1, 0, 1}, dj[4] = {0, 1, 1, 1};
  for (std::size_t k = 0; k < nodes_.size(); ++k)
    for (int d = 0; d < 4; ++d) {
      const int i = column(k) + di[d], j = row(k) + dj[d];
      if (i < 0 || j < 0 || i >= nx_ || j >= ny_) continue;
      const int m = node_of_[j * nx_ + i];
      if (m < 0 || !space.segment_free(nodes_[k], nodes_[m])) continue;
      const double length = norm(nodes_[m] - nodes_[k]);
      adjacent[k].push_back({m, length});
      adjacent[m].push_back({static_cast<int>(k), length});
    }
  link_begin_.assign(1, 0);
  for (const auto& a : adjacent) {
    links_.insert(links_.end(), a.begin(), a.end());
    link_begin_.push_back(static_cast<int>(links_.size()));
  }
}

std::vector<double> GridRoadmap::distances_from(Vec2 from, std::vector<int>* previous) const {
  std::vector<double> dist(nodes_.size(), kUnreachable);
  if (previous) previous->assign(nodes_.size(), -1);
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> open;
  // Seeds: the nodes of the lattice cells around `from` that it sees free.
  const int ci = static_cast<int>(std::floor((from.x - first_.x) / spacing_));
  const int cj = static_cast<int>(std::floor((from.y - first_.y) / spacing_));
  for (int j = cj - 1; j <= cj + 2; ++j)
    for (int i = ci - 1; i <= ci + 2; ++i) {
      if (i < 0 || j < 0 || i >= nx_ || j >= ny_) continue;
      const int k = node_of_[j * nx_ + i];
      if (k < 0 || !space_.segment_free(from, nodes_[k])) continue;
      const double d = norm(nodes_[k] - from);
      if (d < dist[k]) open.emplace(dist[k] = d, k);
    }
  while (!open.empty()) {
    const auto [d, k] = open.top();
    open.pop();
    if (d > dist[k]) continue;
    for (int e = link_begin_[k]; e < link_begin_[k + 1]; ++e) {
      const Link& l = links_[e];
      if (d + l.length < dist[l.to]) {
        open.emplace(dist[l.to] = d + l.length, l.to);
        if (previous) (*previous)[l.to] = k;
      }
    }
  }
  return dist;
}

}  // namespace plumekit::planner
