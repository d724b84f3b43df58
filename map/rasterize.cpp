#include "map/rasterize.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/memory_limit.hpp"

namespace plumekit {

GridShape GridShape::with_cell(double width, double height, double cell) {
  GridShape s;
  s.width = width;
  s.height = height;
  s.nx = std::max(1, static_cast<int>(std::lround(width / cell)));
  s.ny = std::max(1, static_cast<int>(std::lround(height / cell)));
  return s;
}

GridShape::Bilinear GridShape::bilinear(Vec2 p) const {
  auto axis = [](double g, int n, int& i0, int& i1, double& t) {
    g = std::clamp(g - 0.5, 0.0, static_cast<double>(n - 1));
    i0 = std::min(static_cast<int>(g), std::max(n - 2, 0));
    i1 = std::min(i0 + 1, n - 1);
    t = n > 1 ? g - i0 : 0.0;
  };
  Bilinear b;
  axis(p.x / dx(), nx, b.i0, b.i1, b.tx);
  axis(p.y / dy(), ny, b.j0, b.j1, b.ty);
  return b;
}

namespace {

void check_raster_memory(const GridShape& shape) {
  check_memory(static_cast<double>(shape.nx) * shape.ny * kRasterBytesPerCell,
               "rasterizing the map on " + std::to_string(shape.nx) + " x " +
                   std::to_string(shape.ny) + " cells",
               "use larger cells");
}

// The edges (index of their first vertex) that covers(poly, p) can consult
// for a point at height y: those whose y-range, widened by within_box's
// tolerance (core/geometry.cpp), holds y. A real map's outline has thousands
// of edges, of which a row meets a few.
void row_edges(const Polygon& poly, double y, std::vector<std::size_t>& edges) {
  edges.clear();
  for (std::size_t i = 0, n = poly.size(); i < n; ++i) {
    const Vec2 a = poly[i], b = poly[(i + 1) % n];
    const double tol =
        2e-12 * std::max({std::abs(a.x), std::abs(a.y), std::abs(b.x), std::abs(b.y), 1.0});
    if (y >= std::min(a.y, b.y) - tol && y <= std::max(a.y, b.y) + tol) edges.push_back(i);
  }
}

// covers(poly, p) over the row's edges only: the same answer, since an edge
// off the row can neither hold p nor cross its ray (locate's rules).
bool covers_on_row(const Polygon& poly, const std::vector<std::size_t>& edges, Vec2 p) {
  bool inside = false;
  for (std::size_t i : edges) {
    const Vec2 a = poly[i], b = poly[(i + 1) % poly.size()];
    if (point_on_segment(p, a, b)) return true;
    if ((a.y > p.y) != (b.y > p.y) && p.x < a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y))
      inside = !inside;
  }
  return inside;
}

}  // namespace

Grid<std::uint8_t> rasterize_occupancy(const Map& map, const GridShape& shape) {
  check_raster_memory(shape);
  Grid<std::uint8_t> grid(shape, 0);
  for (const Polygon& poly : map.obstacles) {
    // Only the cells whose centres fall in the polygon's bounding box can be solid.
    const Box box = bounding_box(poly);
    const int i0 = std::max(0, static_cast<int>(std::floor(box.lo.x / shape.dx() - 0.5)));
    const int i1 = std::min(shape.nx - 1, static_cast<int>(std::ceil(box.hi.x / shape.dx() - 0.5)));
    const int j0 = std::max(0, static_cast<int>(std::floor(box.lo.y / shape.dy() - 0.5)));
    const int j1 = std::min(shape.ny - 1, static_cast<int>(std::ceil(box.hi.y / shape.dy() - 0.5)));
    std::vector<std::size_t> edges;
    for (int j = j0; j <= j1; ++j) {
      row_edges(poly, shape.centre(0, j).y, edges);
      for (int i = i0; i <= i1; ++i) {
        if (!grid(i, j) && covers_on_row(poly, edges, shape.centre(i, j))) grid(i, j) = 1;
      }
    }
  }
  return grid;
}

namespace {

std::uint8_t opening_label(const Map& map, int k) {
  return map.openings[static_cast<std::size_t>(k)].is_inlet() ? kInlet : kOutlet;
}

}  // namespace

Grid<std::uint8_t> rasterize_labels(const Map& map, const GridShape& shape) {
  return rasterize_labels(map, rasterize_occupancy(map, shape));
}

Grid<std::uint8_t> rasterize_labels(const Map& map, const Grid<std::uint8_t>& solid) {
  const GridShape& shape = solid.shape;
  Grid<std::uint8_t> labels(shape, kFree);
  const double hx = 0.5 * shape.dx(), hy = 0.5 * shape.dy();
  for (int j = 0; j < shape.ny; ++j) {
    for (int i = 0; i < shape.nx; ++i) {
      if (solid(i, j)) {
        labels(i, j) = kObstacle;
        continue;
      }
      const Vec2 c = shape.centre(i, j);
      std::uint8_t label = kFree;
      // A face of the cell on the free space's boundary: an arena edge (a wall
      // unless an opening covers it) or a solid neighbour (only an opening
      // labels it). Openings win over plain wall at corners.
      auto face = [&](int ni, int nj, bool vertical, double line, double s) {
        const bool edge = !shape.contains(ni, nj);
        if (!edge && !solid(ni, nj)) return;
        const int k = map.opening_on_line(vertical, line, vertical ? hx : hy, s);
        if (k < 0 && !edge) return;
        const std::uint8_t l = k >= 0 ? opening_label(map, k) : std::uint8_t{kWall};
        if (label == kFree || (label == kWall && l != kWall)) label = l;
      };
      face(i - 1, j, true, i * shape.dx(), c.y);
      face(i + 1, j, true, (i + 1) * shape.dx(), c.y);
      face(i, j - 1, false, j * shape.dy(), c.x);
      face(i, j + 1, false, (j + 1) * shape.dy(), c.x);
      labels(i, j) = label;
    }
  }
  return labels;
}

bool inlet_reaches_outlet(const Grid<std::uint8_t>& labels) {
  const GridShape& s = labels.shape;
  std::vector<char> seen(s.size(), 0);
  std::vector<std::pair<int, int>> stack;
  for (int j = 0; j < s.ny; ++j)
    for (int i = 0; i < s.nx; ++i)
      if (labels(i, j) == kInlet) {
        seen[s.index(i, j)] = 1;
        stack.emplace_back(i, j);
      }
  while (!stack.empty()) {
    const auto [i, j] = stack.back();
    stack.pop_back();
    if (labels(i, j) == kOutlet) return true;
    const int di[] = {1, -1, 0, 0}, dj[] = {0, 0, 1, -1};
    for (int k = 0; k < 4; ++k) {
      const int a = i + di[k], b = j + dj[k];
      if (!s.contains(a, b) || seen[s.index(a, b)] || labels(a, b) == kObstacle) continue;
      seen[s.index(a, b)] = 1;
      stack.emplace_back(a, b);
    }
  }
  return false;
}

MapGridCheck map_grid_check(const Map& map, double cell, double max_cells) {
  MapGridCheck c;
  // Cell counts in double: a huge arena at a small cell overflows an int.
  const double cells = std::round(map.width / cell) * std::round(map.height / cell);
  if (cells > max_cells) {
    cell = std::sqrt(map.width * map.height / max_cells);
    // Round-off in the counts may leave one row or column too many.
    while (std::round(map.width / cell) * std::round(map.height / cell) > max_cells)
      cell *= 1.001;
    c.coarsened = true;
  }
  c.shape = GridShape::with_cell(map.width, map.height, cell);
  c.cell = std::max(c.shape.dx(), c.shape.dy());
  const Grid<std::uint8_t> labels = rasterize_labels(map, c.shape);
  std::size_t free = 0;
  for (auto v : labels.values)
    free += v != kObstacle;
  c.free_fraction = static_cast<double>(free) / static_cast<double>(labels.values.size());
  c.inlet_reaches_outlet = inlet_reaches_outlet(labels);
  return c;
}

}  // namespace plumekit
