#include "cfd/grid_check.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/error.hpp"
#include "core/memory_limit.hpp"
#include "core/option_check.hpp"
#include "map/connectivity.hpp"
#include "map/rasterize.hpp"

namespace plumekit::cfd {

namespace {

// The cell size (rounded up to 2 significant digits) that gives at most
// `cells` cells on the map's arena.
double cell_for(const Map& map, double cells) {
  const double exact = std::sqrt(map.width * map.height / cells);
  const double scale = std::pow(10.0, std::floor(std::log10(exact)) - 1);
  double cell = std::ceil(exact / scale * (1 + 1e-9)) * scale;
  // Each side's count is rounded, which may add a row or column: step up until it fits.
  while (std::round(map.width / cell) * std::round(map.height / cell) > cells)
    cell += scale;
  return cell;
}

// "a cell of 0.012 m or finer keeps every gap open", and whether a solve
// could take that grid.
std::string open_cell_advice(const Map& map, double narrowest) {
  const double open = cell_keeping_gaps_open(map, narrowest);
  std::ostringstream s;
  s << "use a cell of " << compact(open) << " m or finer to keep every gap open";
  const double cells = std::round(map.width / open) * std::round(map.height / open);
  if (cells > kMaxFlowCells || !fits_in_memory(flow_memory_estimate(cells)))
    s << " (" << compact(cells) << " cells: more than a solve here can take)";
  return s.str();
}

// Whether air passes from an inlet to an outlet on the grid of `cell` with its
// own narrow gaps closed; false also for a grid a solve could not take.
bool passes_at(const Map& map, double cell) {
  const double cells = std::round(map.width / cell) * std::round(map.height / cell);
  if (cells > kMaxFlowCells || !fits_in_memory(flow_memory_estimate(cells))) return false;
  const GridShape shape = GridShape::with_cell(map.width, map.height, cell);
  Grid<std::uint8_t> solid = rasterize_occupancy(map, shape);
  close_narrow_gaps(map, shape, solid.values);
  return inlet_reaches_outlet(rasterize_labels(map, solid));
}

// The largest cell finer than `cell` at which the closed grid lets air pass,
// each candidate checked on its own grid, or 0. The candidates keep the gaps
// from the widest down open (cell_keeping_gaps_open); more open gaps mostly
// mean more passage, so the search bisects their list (a few grids).
double passing_cell(const Map& map, const std::vector<GapReport>& gaps, double cell) {
  std::vector<double> candidates;  // descending
  for (auto g = gaps.rbegin(); g != gaps.rend(); ++g) {
    const double c = cell_keeping_gaps_open(map, g->width);
    if (c < cell && (candidates.empty() || c < candidates.back())) candidates.push_back(c);
  }
  double found = 0.0;
  std::size_t lo = 0, hi = candidates.size();  // the answer's index lies in [lo, hi)
  while (lo < hi) {
    const std::size_t mid = (lo + hi) / 2;
    if (passes_at(map, candidates[mid]))
      found = candidates[mid], hi = mid;
    else
      lo = mid + 1;
  }
  return found;
}

// Closing the narrow gaps cut every inlet off from every outlet (the map's own
// rasterization does not): names the narrowest closed gap at the edge of the
// region the inlets reach, and the cell that keeps the gaps open.
[[noreturn]] void sealed_by_gaps(const Map& map, const Grid<std::uint8_t>& solid,
                                 const std::vector<int>& closed_by,
                                 const std::vector<GapReport>& gaps, double cell) {
  const Grid<std::uint8_t> labels = rasterize_labels(map, solid);
  const GridShape& s = labels.shape;
  std::vector<char> reached(s.size(), 0);
  std::vector<std::size_t> queue;
  for (std::size_t k = 0; k < s.size(); ++k)
    if (labels.values[k] == kInlet) reached[k] = 1, queue.push_back(k);
  int responsible = -1;  // gaps are sorted narrowest first: the smallest index
  for (std::size_t q = 0; q < queue.size(); ++q) {
    const int i = static_cast<int>(queue[q] % s.nx), j = static_cast<int>(queue[q] / s.nx);
    const int di[] = {1, -1, 0, 0}, dj[] = {0, 0, 1, -1};
    for (int n = 0; n < 4; ++n) {
      if (!s.contains(i + di[n], j + dj[n])) continue;
      const std::size_t k = s.index(i + di[n], j + dj[n]);
      if (const int g = closed_by[k]; g >= 0 && (responsible < 0 || g < responsible))
        responsible = g;
      if (reached[k] || labels.values[k] == kObstacle) continue;
      reached[k] = 1;
      queue.push_back(k);
    }
  }
  if (responsible < 0) responsible = 0;
  std::ostringstream m;
  m << compact(cell) << " m: closing the " << gaps.size() << (gaps.size() == 1 ? " gap" : " gaps")
    << " narrower than one cell (open in the map) seals every inlet from every outlet, so no "
    << "flow can pass; the narrowest closed gap the inlets' air reaches: "
    << describe_gap(map, gaps[static_cast<std::size_t>(responsible)]) << "; ";
  if (const double passing = passing_cell(map, gaps, cell); passing > 0.0)
    m << "at a cell of " << compact(passing) << " m air passes (checked on that grid); ";
  m << open_cell_advice(map, gaps.front().width) << ", or widen the gaps in the map";
  throw OptionError("flow.cell", m.str());
}

// No free path on the grid. When an opening is shorter than a cell the grid,
// not the map, is at fault (a huge arena's default cell is coarse): say so,
// with the cell that fits.
[[noreturn]] void no_path(const Map& map, const GridShape& shape, const FlowOptions& options) {
  const std::vector<MissedOpening> missed = openings_missed_by_grid(map, shape);
  if (missed.empty())
    throw InputError(
        "map: no free path from the inlet to the outlet on this grid, so no flow can pass; "
        "open a passage or move the openings");
  const MissedOpening& m = missed.front();
  const double fit = cell_keeping_gaps_open(map, m.length);
  const double cells = std::round(map.width / fit) * std::round(map.height / fit);
  std::ostringstream s;
  s << compact(resolved_cell(map, options)) << " m cells";
  if (options.cell == 0.0)
    s << " (the default on a " << compact(map.width) << " x " << compact(map.height) << " m arena)";
  s << " are too coarse for this map: " << opening_name(map, m.index) << " is " << compact(m.length)
    << " m long, shorter than a cell, so no cell opens onto it and no flow "
    << "can pass; a cell of " << compact(fit) << " m or finer opens onto every opening";
  if (cells > kMaxFlowCells || !fits_in_memory(flow_memory_estimate(cells)))
    s << ", but gives " << compact(cells) << " cells, more than a solve here can take: split the "
      << "map into smaller ones, or make the openings longer";
  throw OptionError("flow.cell", s.str());
}

}  // namespace

double flow_memory_estimate(double cells) {
  // See docs/design/flow-solver.md, "Memory estimate": bytes per cell grow with log2(cells), as the
  // LU's fill under nested dissection does, plus the process's own baseline.
  // Square arenas fill more than elongated ones of as many cells, so the
  // constants fit the square ones: 40000 cells 301 MB, 160000 1.27 GB; the
  // 10 x 4 m arena's 16000 cells take 92 MB (estimate 150 MB).
  constexpr double kBaseline = 40e6, kPerCell = 1000.0, kPerCellLog = 420.0;
  return kBaseline + cells * (kPerCell + kPerCellLog * std::log2(std::max(cells, 2.0)));
}

void check_grid_size(const Map& map, const FlowOptions& options) {
  const double cell = resolved_cell(map, options);
  const double nx = std::round(map.width / cell), ny = std::round(map.height / cell);
  if (nx < 3 || ny < 3) {
    std::ostringstream s;
    s << compact(cell) << " m gives a " << compact(nx) << " x " << compact(ny) << " grid on the "
      << compact(map.width) << " x " << compact(map.height)
      << " m arena; at least 3 cells per side are needed: use a cell of at most "
      << compact(std::min(map.width, map.height) / 3) << " m";
    throw OptionError("flow.cell", s.str());
  }
  const double cells = nx * ny;
  if (cells > kMaxFlowCells) {
    std::ostringstream s;
    s << compact(cell) << " m gives " << compact(cells) << " cells on the " << compact(map.width)
      << " x " << compact(map.height) << " m arena, more than the " << compact(kMaxFlowCells)
      << " a solve can handle; ";
    const double fits = cell_for(map, kMaxFlowCells);
    if (fits <= kMaxCell)
      s << "use a cell of at least " << compact(fits) << " m";
    else
      s << "even the largest cell, " << compact(kMaxCell)
        << " m, is too fine for an arena this size: split the map into smaller ones";
    throw OptionError("flow.cell", s.str());
  }
  const double bytes = flow_memory_estimate(cells);
  if (!fits_in_memory(bytes)) {
    // The largest cell count whose estimate fits, by bisection (the estimate grows with cells).
    double lo = 0.0, hi = cells;
    for (int k = 0; k < 60; ++k) {
      const double mid = 0.5 * (lo + hi);
      (fits_in_memory(flow_memory_estimate(mid)) ? lo : hi) = mid;
    }
    std::ostringstream what, fix;
    what << "the flow solve on " << compact(nx) << " x " << compact(ny) << " cells of "
         << compact(cell) << " m";
    if (lo >= 9.0) fix << "use a larger flow.cell (" << compact(cell_for(map, lo)) << " m fits)";
    check_memory(bytes, what.str(), fix.str());
  }
}

std::vector<GapReport> check_grid(const Map& map, const GridShape& shape,
                                  const FlowOptions& options) {
  Grid<std::uint8_t> solid = rasterize_occupancy(map, shape);
  std::vector<int> closed_by;
  std::vector<GapReport> gaps = close_narrow_gaps(map, shape, solid.values, &closed_by);
  const double cell = resolved_cell(map, options);
  if (!gaps.empty() && options.strict_gaps) {
    std::ostringstream s;
    s << compact(cell) << " m: " << gaps.size()
      << (gaps.size() == 1 ? " gap between obstacles (or an obstacle and a wall) is"
                           : " gaps between obstacles (or an obstacle and a wall) are")
      << " open in the map but narrower than one cell, and flow.strict_gaps refuses to close "
      << "them; the narrowest: " << describe_gap(map, gaps.front()) << "; "
      << open_cell_advice(map, gaps.front().width) << ", or close or widen the gaps in the map";
    throw OptionError("flow.cell", s.str());
  }
  if (!options.closed && !inlet_reaches_outlet(rasterize_labels(map, solid))) {
    if (!gaps.empty() && inlet_reaches_outlet(rasterize_labels(map, shape)))
      sealed_by_gaps(map, solid, closed_by, gaps, cell);
    no_path(map, shape, options);
  }
  return gaps;
}

}  // namespace plumekit::cfd
