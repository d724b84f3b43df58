#include "planner/inflation.hpp"

#include <cmath>
#include <iterator>
#include <type_traits>
#include <utility>

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Polygon_2.h>
#include <CGAL/Polygon_set_2.h>
#include <CGAL/Polygon_with_holes_2.h>
#include <CGAL/minkowski_sum_2.h>

#include "core/error.hpp"
#include "core/option_check.hpp"
#include "planner/planner.hpp"

namespace plumekit::planner {

namespace {

using K = CGAL::Exact_predicates_exact_constructions_kernel;
using Point = K::Point_2;
using CPolygon = CGAL::Polygon_2<K>;
using CPolygonWithHoles = CGAL::Polygon_with_holes_2<K>;
using CPolygonSet = CGAL::Polygon_set_2<K>;

CPolygon to_cgal(const Polygon& poly) {
  CPolygon out;
  for (Vec2 v : poly)
    out.push_back(Point(v.x, v.y));
  if (out.is_clockwise_oriented()) out.reverse_orientation();
  return out;
}

// The double nearest to an exact coordinate, so that e.g. 2 - 0.15 comes back
// as the double 1.85 that a user types.
double nearest_double(const K::FT& value) {
  const auto& exact = CGAL::exact(value);
  using Exact = std::decay_t<decltype(exact)>;
  const std::pair<double, double> bounds = CGAL::to_interval(exact);
  if (bounds.first == bounds.second) return bounds.first;
  const Exact below = exact - Exact(bounds.first), above = Exact(bounds.second) - exact;
  return above < below ? bounds.second : bounds.first;
}

// Rounds once to doubles; drops a vertex that rounds onto its predecessor.
Polygon to_doubles(const CPolygon& poly) {
  Polygon out;
  for (auto it = poly.vertices_begin(); it != poly.vertices_end(); ++it) {
    const Vec2 v{nearest_double(it->x()), nearest_double(it->y())};
    if (out.empty() || out.back() != v) out.push_back(v);
  }
  while (out.size() > 1 && out.front() == out.back())
    out.pop_back();
  return out;
}

}  // namespace

Polygon circumscribed_ngon(double r, int n) {
  // Vertex k sits at angle (k + 1/2) 2 pi / n, at distance r / cos(pi / n):
  // each edge is tangent to the circle at angle k 2 pi / n.
  Polygon out;
  const double pi = std::acos(-1.0);
  const double rv = r / std::cos(pi / n);
  for (int k = 0; k < n; ++k) {
    const double a = (k + 0.5) * 2.0 * pi / n;
    out.push_back({rv * std::cos(a), rv * std::sin(a)});
  }
  if (n % 4 == 0) {
    // Snap the vertices of the axis-facing edges onto x = +-r and y = +-r, so
    // that a wall at x = 2 offsets to exactly 2 - r, as a user would type it.
    const int q = n / 4;
    for (int side = 0; side < 4; ++side) {
      // Edge tangent at angle side * pi/2 joins vertices side*q - 1 and side*q.
      const int v0 = (side * q + n - 1) % n, v1 = side * q;
      for (int v : {v0, v1}) {
        if (side % 2 == 0)
          out[v].x = side == 0 ? r : -r;
        else
          out[v].y = side == 1 ? r : -r;
      }
    }
  }
  return out;
}

double inflation_error_bound(double margin, int n) {
  return margin * (1.0 / std::cos(std::acos(-1.0) / n) - 1.0);
}

std::vector<Region> inflate_free_space(const Map& map, double margin, int arc_segments) {
  PlannerOptions checked;  // the planner's own checks of the two numbers
  checked.margin = margin;
  checked.arc_segments = arc_segments;
  validate_entry(planner_option_table().entry("planner.margin"), checked);
  validate_entry(planner_option_table().entry("planner.arc_segments"), checked);
  std::vector<Region> regions;
  const double x0 = margin, y0 = margin, x1 = map.width - margin, y1 = map.height - margin;
  if (!(x1 > x0) || !(y1 > y0)) return regions;  // the arena is narrower than two margins

  // Each obstacle grown on its own, then all of them joined: overlapping and
  // touching ones merge, and the regularized union keeps no zero-width slivers.
  std::vector<CPolygonWithHoles> grown;
  grown.reserve(map.obstacles.size());
  const CPolygon disk =
      margin > 0.0 ? to_cgal(circumscribed_ngon(margin, arc_segments)) : CPolygon();
  for (const Polygon& obstacle : map.obstacles) {
    const CPolygon p = to_cgal(obstacle);
    grown.push_back(margin > 0.0 ? CGAL::minkowski_sum_2(p, disk) : CPolygonWithHoles(p));
  }
  CPolygonSet blocked;
  if (!grown.empty()) blocked.join(grown.begin(), grown.end());

  CPolygon arena;
  arena.push_back(Point(x0, y0));
  arena.push_back(Point(x1, y0));
  arena.push_back(Point(x1, y1));
  arena.push_back(Point(x0, y1));
  CPolygonSet free_space(arena);
  free_space.difference(blocked);

  std::vector<CPolygonWithHoles> pieces;
  free_space.polygons_with_holes(std::back_inserter(pieces));
  for (const CPolygonWithHoles& piece : pieces) {
    Region r;
    CPolygon outer = piece.outer_boundary();
    if (outer.is_clockwise_oriented()) outer.reverse_orientation();
    r.outer = to_doubles(outer);
    for (auto h = piece.holes_begin(); h != piece.holes_end(); ++h) {
      CPolygon hole = *h;
      if (hole.is_counterclockwise_oriented()) hole.reverse_orientation();
      r.holes.push_back(to_doubles(hole));
    }
    if (r.outer.size() >= 3) regions.push_back(std::move(r));
  }
  return regions;
}

}  // namespace plumekit::planner
