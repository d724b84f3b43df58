#pragma once
// Refuses grids that cannot represent the map's flow, or that would not fit
// in memory: too few or too many cells, a solve whose estimated peak memory
// exceeds the limit (core/memory_limit.hpp), a gap between obstacles (or an
// obstacle and a wall) that is open in the map but narrower than one cell, or
// an inlet with no way to the outlet. Faults of the cell size are OptionErrors
// on "flow.cell".
#include "cfd/options.hpp"
#include "core/grid.hpp"
#include "core/map.hpp"

namespace plumekit::cfd {

// Most cells a flow grid may have: a solve on 4 million cells takes hours.
inline constexpr double kMaxFlowCells = 4e6;
// The largest cell FlowOptions::validate accepts, m.
inline constexpr double kMaxCell = 10.0;

// Estimated peak memory (bytes) of cfd::solve on a grid of `cells` cells: the
// sparse LU's fill grows a little faster than the cell count. Calibrated on
// measured peak RSS (cfd/README.md, "Memory").
double flow_memory_estimate(double cells);

// The grid size checks, before any grid is made: at least 3 cells per side,
// at most kMaxFlowCells, and the memory estimate within the limit (each
// message names the cell size that would fit). Throws OptionError on
// "flow.cell" or MemoryLimitError.
void check_grid_size(const Map& map, const FlowOptions& options);

// The checks that need the grid: narrow gaps and inlet-to-outlet connectivity.
void check_grid(const Map& map, const GridShape& shape, const FlowOptions& options);

}  // namespace plumekit::cfd
