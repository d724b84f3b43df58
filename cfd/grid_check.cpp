#include "cfd/grid_check.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/error.hpp"
#include "core/memory_limit.hpp"
#include "core/option_check.hpp"
#include "core/rasterize.hpp"

namespace plumekit::cfd {

namespace {

double segment_distance(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
  if (segments_intersect(a, b, c, d)) return 0.0;
  return std::min({distance_to_segment(a, c, d), distance_to_segment(b, c, d),
                   distance_to_segment(c, a, b), distance_to_segment(d, a, b)});
}

double polygon_distance(const Polygon& p, const Polygon& q) {
  double best = HUGE_VAL;
  for (std::size_t i = 0; i < p.size(); ++i)
    for (std::size_t j = 0; j < q.size(); ++j)
      best = std::min(best,
                      segment_distance(p[i], p[(i + 1) % p.size()], q[j], q[(j + 1) % q.size()]));
  return best;
}

// Distance from a polygon inside the arena to one wall (it is at a vertex).
double wall_distance(const Map& map, const Polygon& p, Side side) {
  double best = HUGE_VAL;
  for (Vec2 v : p) {
    const double d = side == Side::Left     ? v.x
                     : side == Side::Right  ? map.width - v.x
                     : side == Side::Bottom ? v.y
                                            : map.height - v.y;
    best = std::min(best, d);
  }
  return best;
}

[[noreturn]] void narrow_gap(const std::string& what, double gap, double cell) {
  std::ostringstream s;
  s << compact(cell) << " m: " << what << " are " << compact(gap)
    << " m apart, less than one cell, so the grid would close a gap that is open in the map; "
    << "use a cell of " << compact(gap / 2) << " m or finer, or close or widen the gap in the map";
  throw OptionError("flow.cell", s.str());
}

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

}  // namespace

double flow_memory_estimate(double cells) {
  // See cfd/README.md, "Memory": bytes per cell grow with log2(cells), as the
  // LU's fill under nested dissection does, plus the process's own baseline.
  // Square arenas fill more than elongated ones of as many cells, so the
  // constants fit the square ones: 40000 cells 301 MB, 160000 1.27 GB; the
  // 10 x 4 m arena's 16000 cells take 92 MB (estimate 150 MB).
  constexpr double kBaseline = 40e6, kPerCell = 1000.0, kPerCellLog = 420.0;
  return kBaseline + cells * (kPerCell + kPerCellLog * std::log2(std::max(cells, 2.0)));
}

void check_grid_size(const Map& map, const FlowOptions& options) {
  const double nx = std::round(map.width / options.cell),
               ny = std::round(map.height / options.cell);
  if (nx < 3 || ny < 3) {
    std::ostringstream s;
    s << compact(options.cell) << " m gives a " << compact(nx) << " x " << compact(ny)
      << " grid on the " << compact(map.width) << " x " << compact(map.height)
      << " m arena; at least 3 cells per side are needed: use a cell of at most "
      << compact(std::min(map.width, map.height) / 3) << " m";
    throw OptionError("flow.cell", s.str());
  }
  const double cells = nx * ny;
  if (cells > kMaxFlowCells) {
    std::ostringstream s;
    s << compact(options.cell) << " m gives " << compact(cells) << " cells on the "
      << compact(map.width) << " x " << compact(map.height) << " m arena, more than the "
      << compact(kMaxFlowCells) << " a solve can handle; ";
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
         << compact(options.cell) << " m";
    if (lo >= 9.0) fix << "use a larger flow.cell (" << compact(cell_for(map, lo)) << " m fits)";
    check_memory(bytes, what.str(), fix.str());
  }
}

void check_grid(const Map& map, const GridShape& shape, const FlowOptions& options) {
  const double cell = std::max(shape.dx(), shape.dy());
  for (std::size_t i = 0; i < map.obstacles.size(); ++i) {
    for (std::size_t j = i + 1; j < map.obstacles.size(); ++j) {
      const double d = polygon_distance(map.obstacles[i], map.obstacles[j]);
      if (d > 0.0 && d < cell)
        narrow_gap("obstacles[" + std::to_string(i) + "] and obstacles[" + std::to_string(j) + "]",
                   d, options.cell);
    }
    for (Side side : {Side::Left, Side::Right, Side::Bottom, Side::Top}) {
      const double d = wall_distance(map, map.obstacles[i], side);
      if (d > 0.0 && d < cell)
        narrow_gap("obstacles[" + std::to_string(i) + "] and the " + to_string(side) + " wall", d,
                   options.cell);
    }
  }
  if (!options.closed && !inlet_reaches_outlet(rasterize_labels(map, shape)))
    throw InputError(
        "map: no free path from the inlet to the outlet on this grid, so no flow can pass; "
        "open a passage or move the openings");
}

}  // namespace plumekit::cfd
