#pragma once
// Map -> label grid. The rule: a cell is solid when its centre lies inside an
// obstacle or on an obstacle's boundary. Free cells that touch the arena's
// edge take the label of that wall: inlet or outlet when the centre's position
// along the wall lies within the opening's span, plain wall otherwise (a corner
// cell takes an opening's label if either of its walls has one there).
#include <cstdint>

#include "core/grid.hpp"
#include "core/map.hpp"

namespace plumekit {

// Region labels, the values the CNN's first feature map uses.
enum Label : std::uint8_t {
  kObstacle = 0,
  kFree = 1,
  kWall = 2,
  kInlet = 3,
  kOutlet = 4,
};

Grid<std::uint8_t> rasterize_labels(const Map& map, const GridShape& shape);

// 1 for solid cells, 0 for free ones (same rule as the labels).
Grid<std::uint8_t> rasterize_occupancy(const Map& map, const GridShape& shape);

// Whether some inlet cell reaches some outlet cell through free cells
// (4-neighbours), i.e. whether air can flow through the map at all.
bool inlet_reaches_outlet(const Grid<std::uint8_t>& labels);

}  // namespace plumekit
