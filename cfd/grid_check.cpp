#include "cfd/grid_check.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/error.hpp"
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
  s << "--cell " << cell << ": " << what << " are " << gap << " m apart, less than one cell, "
    << "so the grid would close a gap that is open in the map. Use --cell " << gap / 2
    << " or finer, or close the gap in the map.";
  throw InputError(s.str());
}

}  // namespace

void check_grid(const Map& map, const GridShape& shape, const FlowOptions& options) {
  if (shape.nx < 3 || shape.ny < 3) {
    std::ostringstream s;
    s << "--cell " << options.cell << ": gives a " << shape.nx << " x " << shape.ny
      << " grid; at least 3 cells per side are needed";
    throw InputError(s.str());
  }
  if (shape.size() > 4'000'000)
    throw InputError("--cell " + std::to_string(options.cell) +
                     ": more than 4 million cells; use a coarser cell");

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
