#pragma once
// Whether a point is free of obstacles, answered per flow cell (issue 45): most cells are clear
// or wholly inside an obstacle, and decide without a polygon test; a cell an obstacle's edge
// passes near tests only the obstacles whose edges do. The same answer as Map::is_free, at the
// cost of one or two polygons instead of every obstacle of the map (a building has hundreds).
#include <cstdint>
#include <vector>

#include "core/grid.hpp"
#include "map/map.hpp"

namespace plumekit::world {

class ObstacleCells {
 public:
  ObstacleCells(const Map& map, const GridShape& cells);
  // Map::is_free(p), for p in the arena.
  bool free(Vec2 p) const {
    const int i = std::min(cells_.nx - 1, static_cast<int>(p.x * inv_dx_));
    const int j = std::min(cells_.ny - 1, static_cast<int>(p.y * inv_dy_));
    const std::size_t c = cells_.index(i, j);
    if (kind_[c] != kMixed) return kind_[c] == kClear;
    for (int k = first_[c]; k < first_[c + 1]; ++k)
      if (covers(map_.obstacles[static_cast<std::size_t>(near_[k])], p)) return false;
    return true;
  }

 private:
  static constexpr std::uint8_t kClear = 0, kBlocked = 1, kMixed = 2;
  const Map& map_;
  GridShape cells_;
  double inv_dx_, inv_dy_;
  std::vector<std::uint8_t> kind_;  // per cell
  // Mixed cells: the obstacles with an edge within the cell's half-diagonal of its centre,
  // near_[first_[c] .. first_[c + 1]).
  std::vector<int> first_, near_;
};

}  // namespace plumekit::world
