#pragma once
// Which points a filament can reach in a straight line (issue 18, occlusion):
// a filament adds to the concentration at a point only when no obstacle edge
// cuts the segment between them, GADEN's line-of-sight rule. Obstacle edges
// are indexed in square buckets so a query touches only the edges near it.
//
// Only edges that face the viewpoint matter: a segment from a point outside a
// simple polygon that meets the polygon enters it first through an edge whose
// outer side faces that point. Filaments and free sensors are outside every
// obstacle, so "front-facing" edges decide every query (and a point inside an
// obstacle is hidden from the outside by the edge it entered through).
#include <vector>

#include "core/geometry.hpp"
#include "map/map.hpp"

namespace plumekit::world {

struct Edge {
  Vec2 a, b;  // directed so that the obstacle's interior lies on the left
};

class LineOfSight {
 public:
  explicit LineOfSight(const Map& map, double bucket = 1.0);

  // Appends to `out` every edge that meets `box` (by bounding box) and faces
  // `from`; each edge once. A segment inside `box` with one end at `from` can
  // only be cut by these.
  void facing_edges(Vec2 from, const Box& box, std::vector<Edge>& out) const;

 private:
  std::vector<Edge> edges_;
  std::vector<Box> boxes_;         // per edge
  std::vector<int> first_bucket_;  // per edge: its lowest bucket column, row (2 ints)
  std::vector<std::vector<int>> buckets_;
  double bucket_;
  int nx_, ny_;
  int column(double x) const;
  int row(double y) const;
};

// The shadow an edge (facing `from`) casts, row by row: the x-interval of
// the horizontal line y where the segment from `from` to (x, y) meets the
// edge. It is the far side of the edge's line inside the cone from `from`
// through the edge's ends: three half-planes, each linear in x on a row, set
// up once per viewpoint and edge. Closed: a point on the edge's line or on a
// shadow ray counts as hidden.
class EdgeShadow {
 public:
  EdgeShadow(Vec2 from, const Edge& e);
  // The rows the shadow can reach: y in [y_lo(), y_hi()] (possibly infinite).
  double y_lo() const { return y_lo_; }
  double y_hi() const { return y_hi_; }
  // false when the row holds no shadow; lo, hi may be infinite.
  bool on_row(double y, double& lo, double& hi) const;
  // on_row for the rows at y = (j + 0.5) * dy, j = first .. first + n - 1, into lo[] and hi[]
  // (lo > hi where a row holds no shadow): the same numbers, a window's rows in one call without
  // branches.
  void on_rows(int first, int n, double dy, double* lo, double* hi) const;

 private:
  // On a row, each half-plane bounds x from below or above by slope * y + offset.
  struct Bound {
    double slope, offset;
  };
  Bound lower_[3], upper_[3];  // unused ones: 0 * y -/+ infinity (on_rows)
  int lowers_ = 0, uppers_ = 0;
  double y_lo_, y_hi_;
};

// Whether the closed segments [from, p] and [e.a, e.b] meet, for an edge that faces `from`.
bool hides(Vec2 from, const Edge& e, Vec2 p);

}  // namespace plumekit::world
