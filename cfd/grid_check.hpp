#pragma once
// Refuses grids that cannot represent the map's flow, or that would not fit
// in memory: too few or too many cells, a solve whose estimated peak memory
// exceeds the limit (core/memory_limit.hpp), an inlet with no way to the
// outlet; and closes (or, strictly, refuses) gaps between obstacles that are
// open in the map but narrower than one cell. Faults of the cell size are
// OptionErrors on "flow.cell".
#include <vector>

#include "cfd/gap_closing.hpp"
#include "cfd/options.hpp"
#include "core/grid.hpp"
#include "map/map.hpp"

namespace plumekit::cfd {

// Most cells a flow grid may have: a solve on 4 million cells takes hours.
inline constexpr double kMaxFlowCells = 4e6;
// The largest cell FlowOptions::validate accepts, m.
inline constexpr double kMaxCell = 10.0;

// Estimated peak memory (bytes) of cfd::solve on a grid of `cells` cells: the
// sparse LU's fill grows a little faster than the cell count. Calibrated on
// measured peak RSS (docs/design/flow-solver.md, "Memory estimate").
double flow_memory_estimate(double cells);

// The grid size checks, before any grid is made: at least 3 cells per side,
// at most kMaxFlowCells, and the memory estimate within the limit (each
// message names the cell size that would fit). Throws OptionError on
// "flow.cell" or MemoryLimitError.
void check_grid_size(const Map& map, const FlowOptions& options);

// The checks that need the grid: narrow gaps (closed, or refused under
// flow.strict_gaps: gap_closing.hpp) and inlet-to-outlet connectivity on the
// grid with those gaps closed, which the solver uses. Returns the closed gaps,
// narrowest first. Throws OptionError on "flow.cell" (strict gaps, or closed
// gaps that seal the flow: naming the narrowest gap and a cell that keeps the
// gaps open) or InputError (no path from an inlet to an outlet at all).
std::vector<GapReport> check_grid(const Map& map, const GridShape& shape,
                                  const FlowOptions& options);

}  // namespace plumekit::cfd
