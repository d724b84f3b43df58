#pragma once
// Refuses grids that cannot represent the map's flow: too few or too many
// cells, a gap between obstacles (or an obstacle and a wall) that is open in
// the map but narrower than one cell, or an inlet with no way to the outlet.
#include "cfd/options.hpp"
#include "core/grid.hpp"
#include "core/map.hpp"

namespace plumekit::cfd {

void check_grid(const Map& map, const GridShape& shape, const FlowOptions& options);

}  // namespace plumekit::cfd
