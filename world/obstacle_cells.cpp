#include "world/obstacle_cells.hpp"

#include <algorithm>
#include <cmath>

namespace plumekit::world {

ObstacleCells::ObstacleCells(const Map& map, const GridShape& cells)
    : map_(map), cells_(cells), inv_dx_(1.0 / cells.dx()), inv_dy_(1.0 / cells.dy()) {
  const GridShape& s = cells_;
  // Every point of a cell lies within its half-diagonal of the centre: an obstacle whose edges
  // all lie farther covers the whole cell or none of it, as it covers the centre or not.
  const double half_diagonal = 0.5 * std::hypot(s.dx(), s.dy()) * (1.0 + 1e-9);
  std::vector<std::vector<int>> near(s.size());
  std::vector<std::uint8_t> inside(s.size(), 0);
  auto cell_range = [&](double lo, double hi, double size, int n, int& from, int& to) {
    from = std::clamp(static_cast<int>(std::floor((lo - half_diagonal) / size - 0.5)), 0, n - 1);
    to = std::clamp(static_cast<int>(std::ceil((hi + half_diagonal) / size - 0.5)), 0, n - 1);
  };
  for (std::size_t o = 0; o < map.obstacles.size(); ++o) {
    const Polygon& poly = map.obstacles[o];
    if (poly.empty()) continue;
    Vec2 lo = poly[0], hi = poly[0];
    for (const Vec2& v : poly) {
      lo = {std::min(lo.x, v.x), std::min(lo.y, v.y)};
      hi = {std::max(hi.x, v.x), std::max(hi.y, v.y)};
    }
    int i0, i1, j0, j1;
    cell_range(lo.x, hi.x, s.dx(), s.nx, i0, i1);
    cell_range(lo.y, hi.y, s.dy(), s.ny, j0, j1);
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) {
        const Vec2 c = s.centre(i, j);
        bool edge_near = false;
        for (std::size_t k = 0; !edge_near && k < poly.size(); ++k)
          edge_near = distance_to_segment(c, poly[k], poly[(k + 1) % poly.size()]) <= half_diagonal;
        if (edge_near)
          near[s.index(i, j)].push_back(static_cast<int>(o));
        else if (covers(poly, c))
          inside[s.index(i, j)] = 1;
      }
  }
  kind_.assign(s.size(), kClear);
  first_.assign(s.size() + 1, 0);
  for (std::size_t c = 0; c < s.size(); ++c) {
    // Inside one obstacle, the cell is blocked whatever edges of others pass near it.
    if (inside[c])
      kind_[c] = kBlocked;
    else if (!near[c].empty())
      kind_[c] = kMixed;
    if (kind_[c] == kMixed) near_.insert(near_.end(), near[c].begin(), near[c].end());
    first_[c + 1] = static_cast<int>(near_.size());
  }
}

}  // namespace plumekit::world
