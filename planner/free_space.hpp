#pragma once
// The inflated free space with exact queries on it: where a point lies, whether
// a segment stays in free space, the nearest free point. Every predicate is an
// exact orientation or comparison on the doubles of the boundary (CGAL's
// filtered Epick predicates, kept out of this header), so degenerate input
// (collinear vertices, points on the boundary, touching obstacles) is decided
// exactly, never by a tolerance.
//
// Free space is closed: a segment may run along or touch the inflated boundary.
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "core/geometry.hpp"
#include "map/map.hpp"
#include "planner/inflation.hpp"

namespace plumekit::planner {

class FreeSpace {
 public:
  FreeSpace(const Map& map, double margin, int arc_segments);

  const Map& map() const { return map_; }
  double margin() const { return margin_; }
  int arc_segments() const { return arc_segments_; }
  const std::vector<Region>& regions() const { return regions_; }
  bool empty() const { return regions_.empty(); }

  // Inside, on the boundary of, or outside the free space.
  Location locate(Vec2 p) const;
  bool contains(Vec2 p) const { return locate(p) != Location::Outside; }
  // Index into regions() of the piece whose closure holds p, or -1.
  int region_of(Vec2 p) const;
  // The closed segment [a, b] lies in free space. Both ends must be in it.
  bool segment_free(Vec2 a, Vec2 b) const;
  // A point of free space nearest to p (p itself when free). Requires !empty().
  Vec2 nearest_free(Vec2 p) const;

  // Boundary vertices, each distinct point once.
  std::size_t vertex_count() const { return points_.size(); }
  Vec2 vertex(std::size_t i) const { return points_[i]; }
  // A vertex where a shortest path may bend: a convex corner of the inflated
  // obstacles (a reflex corner of free space), or a point where boundaries touch.
  bool is_bend_vertex(std::size_t i) const;
  // Whether the line from vertex i towards q grazes the obstacle at i rather
  // than entering it or leaving it (both boundary neighbours on one side):
  // only such lines can carry a shortest path that bends at i.
  bool tangent_at(std::size_t i, Vec2 q) const;

  // Number of boundary edges (for statistics).
  std::size_t edge_count() const { return edges_.size(); }

 private:
  // One pass of the boundary through a point: the boundary arrives from `u`
  // and leaves towards `w`, with free space on its left.
  struct Pass {
    Vec2 u, w;
  };
  // The boundary passes through a point; a direction from it is free when it
  // lies in as many passes' left sectors as a free direction can (`full`).
  struct Cone {
    std::vector<Pass> passes;
    int full = 0;
  };
  struct Edge {
    Vec2 s, t;
    double xlo, xhi, ylo, yhi;
    std::int32_t start;  // index of s in points_
  };

  static void finish(Cone& cone, Vec2 p);
  static bool direction_free(const Cone& cone, Vec2 p, Vec2 q);
  // The cone at an arbitrary point: its vertex passes, and edges through it.
  Cone cone_at(Vec2 p) const;

  Map map_;
  double margin_;
  int arc_segments_;
  std::vector<Region> regions_;
  std::vector<Edge> edges_;
  std::vector<Vec2> points_;
  std::vector<Cone> cones_;  // per point
  std::unordered_map<Vec2, std::int32_t, Vec2Hash> point_index_;
};

}  // namespace plumekit::planner
