#pragma once
// Map -> label grid. The rule: a cell is solid when its centre lies inside an
// obstacle or on an obstacle's boundary. A free cell whose face lies on an
// opening (Map::opening_on_line: within half a cell of the opening's line,
// the face's middle within its span) takes the opening's label, inlet or
// outlet, whether the face is on an arena wall or against a solid cell; other
// free cells that touch the arena's edge are wall. At a corner the first of
// the left, right, bottom and top faces with an opening decides.
#include <cstdint>

#include "core/grid.hpp"
#include "map/map.hpp"

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
// The labels of a given occupancy (1 solid) on its grid, e.g. one whose narrow
// gaps the flow solver closed (cfd/gap_closing.hpp), so that checks see the
// grid the solver uses.
Grid<std::uint8_t> rasterize_labels(const Map& map, const Grid<std::uint8_t>& solid);

// 1 for solid cells, 0 for free ones (same rule as the labels).
Grid<std::uint8_t> rasterize_occupancy(const Map& map, const GridShape& shape);

// Whether some inlet cell reaches some outlet cell through free cells
// (4-neighbours), i.e. whether air can flow through the map at all.
bool inlet_reaches_outlet(const Grid<std::uint8_t>& labels);

// The rasterizations above hold about this many bytes per cell at their peak
// (the occupancy, the labels and the search's marks); they refuse grids over
// the memory limit (core/memory_limit.hpp) with MemoryLimitError.
inline constexpr double kRasterBytesPerCell = 3.0;

// What `map validate` reports from a grid: the free share of the arena and
// whether air can pass from the inlet to the outlet. The grid has cells of
// `cell` metres unless that would exceed `max_cells`: a huge arena is then
// checked on the coarsest-needed grid (at most max_cells cells), so the check
// takes bounded time and memory whatever the arena's size; `coarsened` says
// so, and a passage narrower than the used cell may then be seen closed.
struct MapGridCheck {
  GridShape shape;
  double cell = 0.0;  // the larger side of the cells used, m
  bool coarsened = false;
  double free_fraction = 0.0;
  bool inlet_reaches_outlet = false;
};
inline constexpr double kMaxCheckCells = 4e6;
MapGridCheck map_grid_check(const Map& map, double cell = 0.05, double max_cells = kMaxCheckCells);

}  // namespace plumekit
