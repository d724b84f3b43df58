#pragma once
// Inflation: obstacles grow by the margin, the arena shrinks by it, and what is
// left is the free space the robot's centre may occupy (CGAL, exact).
#include <vector>

#include "core/geometry.hpp"
#include "map/map.hpp"

namespace plumekit::planner {

// One connected piece of free space. The outer boundary runs counter-clockwise
// and the holes clockwise, so free space is on the left of every edge.
struct Region {
  Polygon outer;
  std::vector<Polygon> holes;
};

// The regular N-gon that circumscribes the disk of radius r about the origin,
// counter-clockwise, with an edge facing each axis when N is a multiple of 4
// (those edges lie exactly on x = +-r, y = +-r).
Polygon circumscribed_ngon(double r, int n);

// How far the N-gon inflation can overshoot the exact offset: r (1/cos(pi/N) - 1).
double inflation_error_bound(double margin, int n);

// The closed free space of `map` at `margin`: the arena shrunk by `margin`,
// minus the union of the obstacles, each grown by the circumscribed N-gon
// (Minkowski sum). Computed with exact constructions (CGAL Epeck) and
// regularized Boolean operations, then rounded once to doubles (error below
// 1e-15 m). Empty when nothing is left.
std::vector<Region> inflate_free_space(const Map& map, double margin, int arc_segments);

}  // namespace plumekit::planner
