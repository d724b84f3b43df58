#include "planner/free_space.hpp"

#include <algorithm>
#include <limits>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

namespace plumekit::planner {

namespace {

// Epick's predicates are exact on doubles (a floating-point filter, with an
// exact fallback only in the near-degenerate cases), and cost a few ns.
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using P = K::Point_2;

inline P pt(Vec2 v) {
  return P(v.x, v.y);
}
// +1 when a, b, c turn counter-clockwise, -1 clockwise, 0 collinear: exactly.
inline int exact_orient(Vec2 a, Vec2 b, Vec2 c) {
  return static_cast<int>(CGAL::orientation(pt(a), pt(b), pt(c)));
}
// Sign of dot(a - p, b - p), exactly.
inline int dot_sign(Vec2 a, Vec2 p, Vec2 b) {
  switch (CGAL::angle(pt(a), pt(p), pt(b))) {
    case CGAL::ACUTE:
      return 1;
    case CGAL::RIGHT:
      return 0;
    default:
      return -1;
  }
}
// For p collinear with a and b: p lies on the closed segment [a, b].
inline bool within(Vec2 a, Vec2 b, Vec2 p) {
  if (a.x != b.x) return std::min(a.x, b.x) <= p.x && p.x <= std::max(a.x, b.x);
  return std::min(a.y, b.y) <= p.y && p.y <= std::max(a.y, b.y);
}
// For p collinear with a and b: p lies strictly between them.
inline bool strictly_within(Vec2 a, Vec2 b, Vec2 p) {
  return p != a && p != b && within(a, b, p);
}

Location ring_locate(const Polygon& ring, Vec2 p) {
  int winding = 0;
  const std::size_t n = ring.size();
  for (std::size_t k = 0; k < n; ++k) {
    const Vec2 s = ring[k], t = ring[(k + 1) % n];
    const int o = exact_orient(s, t, p);
    if (o == 0 && within(s, t, p)) return Location::Boundary;
    if (s.y <= p.y) {
      if (t.y > p.y && o > 0) ++winding;
    } else if (t.y <= p.y && o < 0) {
      --winding;
    }
  }
  return winding != 0 ? Location::Inside : Location::Outside;
}

Vec2 closest_on_segment(Vec2 p, Vec2 a, Vec2 b, double& t) {
  const Vec2 d = b - a;
  const double len2 = dot(d, d);
  t = len2 > 0.0 ? std::clamp(dot(p - a, d) / len2, 0.0, 1.0) : 0.0;
  if (t <= 0.0) return a;
  if (t >= 1.0) return b;
  return a + t * d;
}

// Rounding the exact boundary to doubles can collapse a sliver thinner than
// an ulp into a spike (the ring runs out and straight back) whose free side
// is undecidable locally. Such a sliver has no width: cut it off, and drop
// rings left with no area.
bool clean_ring(Polygon& ring) {
  for (bool changed = true; changed && ring.size() >= 3;) {
    changed = false;
    for (std::size_t k = 0; k < ring.size() && ring.size() >= 3;) {
      const std::size_t n = ring.size();
      const Vec2 u = ring[(k + n - 1) % n], v = ring[k], w = ring[(k + 1) % n];
      if (u == v || (exact_orient(u, v, w) == 0 && dot_sign(u, v, w) >= 0)) {
        ring.erase(ring.begin() + static_cast<std::ptrdiff_t>(k));
        changed = true;
      } else {
        ++k;
      }
    }
  }
  return ring.size() >= 3;
}

}  // namespace

FreeSpace::FreeSpace(const Map& map, double margin, int arc_segments)
    : map_(map),
      margin_(margin),
      arc_segments_(arc_segments),
      regions_(inflate_free_space(map, margin, arc_segments)) {
  std::vector<Region> kept;
  for (Region& r : regions_) {
    if (!clean_ring(r.outer)) continue;
    std::vector<Polygon> holes;
    for (Polygon& h : r.holes)
      if (clean_ring(h)) holes.push_back(std::move(h));
    r.holes = std::move(holes);
    kept.push_back(std::move(r));
  }
  regions_ = std::move(kept);
  auto add_ring = [&](const Polygon& ring) {
    const std::size_t n = ring.size();
    for (std::size_t k = 0; k < n; ++k) {
      const Vec2 u = ring[(k + n - 1) % n], v = ring[k], w = ring[(k + 1) % n];
      auto [it, inserted] = point_index_.try_emplace(v, static_cast<std::int32_t>(points_.size()));
      if (inserted) {
        points_.push_back(v);
        cones_.emplace_back();
      }
      cones_[it->second].passes.push_back({u, w});
      edges_.push_back({v, w, std::min(v.x, w.x), std::max(v.x, w.x), std::min(v.y, w.y),
                        std::max(v.y, w.y), it->second});
    }
  };
  for (const Region& r : regions_) {
    add_ring(r.outer);
    for (const Polygon& h : r.holes)
      add_ring(h);
  }
  // A vertex of one ring may touch the inside of another ring's edge; the edge
  // then bounds free space at that vertex too.
  for (std::size_t i = 0; i < points_.size(); ++i) {
    const Vec2 p = points_[i];
    for (const Edge& e : edges_)
      if (p.x >= e.xlo && p.x <= e.xhi && p.y >= e.ylo && p.y <= e.yhi &&
          exact_orient(e.s, e.t, p) == 0 && strictly_within(e.s, e.t, p))
        cones_[i].passes.push_back({e.s, e.t});
    finish(cones_[i], p);
  }
}

namespace {

// Sign of cross(x - p, d) where d is the direction w - p turned counter-clockwise
// by an infinitesimal angle (symbolic perturbation: never zero).
int perturbed_side(Vec2 p, Vec2 x, Vec2 w) {
  const int c = exact_orient(p, x, w);
  return c != 0 ? c : dot_sign(x, p, w);
}

// The left sector of a pass through p runs counter-clockwise from w - p to u - p.
enum class Sector { Convex, Reflex, Straight, Full };
Sector sector(Vec2 p, Vec2 u, Vec2 w) {
  const int t = exact_orient(p, w, u);
  if (t > 0) return Sector::Convex;
  if (t < 0) return Sector::Reflex;
  return dot_sign(w, p, u) < 0 ? Sector::Straight : Sector::Full;
}

bool in_sector(Sector s, int after_w, int before_u) {
  switch (s) {
    case Sector::Convex:
      return after_w && before_u;
    case Sector::Reflex:
      return after_w || before_u;
    case Sector::Straight:
      return after_w;
    case Sector::Full:
      return true;
  }
  return true;
}

}  // namespace

void FreeSpace::finish(Cone& cone, Vec2 p) {
  // Walking round p, crossing a pass's edge changes how many left sectors hold
  // the direction by one; free directions hold the most. Probe just
  // counter-clockwise of each pass's outgoing edge: every free sector starts there.
  cone.full = 0;
  for (const Pass& probe : cone.passes) {
    int count = 0;
    for (const Pass& q : cone.passes)
      count += in_sector(sector(p, q.u, q.w), perturbed_side(p, q.w, probe.w) > 0,
                         perturbed_side(p, q.u, probe.w) < 0);
    cone.full = std::max(cone.full, count);
  }
}

bool FreeSpace::direction_free(const Cone& cone, Vec2 p, Vec2 q) {
  if (cone.passes.empty()) return true;
  int count = 0;
  for (const Pass& s : cone.passes)
    count +=
        in_sector(sector(p, s.u, s.w), exact_orient(p, s.w, q) >= 0, exact_orient(p, s.u, q) <= 0);
  return count >= cone.full;
}

FreeSpace::Cone FreeSpace::cone_at(Vec2 p) const {
  if (auto it = point_index_.find(p); it != point_index_.end()) return cones_[it->second];
  Cone cone;
  for (const Edge& e : edges_)
    if (p.x >= e.xlo && p.x <= e.xhi && p.y >= e.ylo && p.y <= e.yhi &&
        exact_orient(e.s, e.t, p) == 0 && strictly_within(e.s, e.t, p))
      cone.passes.push_back({e.s, e.t});
  finish(cone, p);
  return cone;
}

Location FreeSpace::locate(Vec2 p) const {
  int winding = 0;
  for (const Edge& e : edges_) {
    const int o = exact_orient(e.s, e.t, p);
    if (o == 0 && within(e.s, e.t, p)) return Location::Boundary;
    if (e.s.y <= p.y) {
      if (e.t.y > p.y && o > 0) ++winding;
    } else if (e.t.y <= p.y && o < 0) {
      --winding;
    }
  }
  // Outer boundaries wind +1 and holes -1 round free points, so free space
  // has winding 1 and obstacles 0, however the pieces nest.
  return winding > 0 ? Location::Inside : Location::Outside;
}

int FreeSpace::region_of(Vec2 p) const {
  for (std::size_t r = 0; r < regions_.size(); ++r) {
    if (ring_locate(regions_[r].outer, p) == Location::Outside) continue;
    bool in_hole = false;
    for (const Polygon& h : regions_[r].holes)
      if (ring_locate(h, p) == Location::Inside) in_hole = true;
    if (!in_hole) return static_cast<int>(r);
  }
  return -1;
}

bool FreeSpace::segment_free(Vec2 a, Vec2 b) const {
  if (a == b) return true;
  const double xlo = std::min(a.x, b.x), xhi = std::max(a.x, b.x);
  const double ylo = std::min(a.y, b.y), yhi = std::max(a.y, b.y);
  // Boundary points the segment touches: its ends (when on an edge) and
  // vertices inside it. Between them it is wholly inside free space or wholly
  // outside, so checking the directions it leaves each contact in decides it.
  Cone at_a, at_b;
  std::int32_t contacts[16];
  int n_contacts = 0;
  std::vector<std::int32_t> more_contacts;
  for (const Edge& e : edges_) {
    if (e.xhi < xlo || e.xlo > xhi || e.yhi < ylo || e.ylo > yhi) continue;
    const int os = exact_orient(a, b, e.s), ot = exact_orient(a, b, e.t);
    if (os == ot && os != 0) continue;  // the edge lies on one side of the line
    const int oa = exact_orient(e.s, e.t, a), ob = exact_orient(e.s, e.t, b);
    if (os == -ot && os != 0 && oa == -ob && oa != 0) return false;  // a proper crossing
    if (os == 0 && strictly_within(a, b, e.s)) {
      if (n_contacts < 16)
        contacts[n_contacts++] = e.start;
      else
        more_contacts.push_back(e.start);
    }
    if (oa == 0 && strictly_within(e.s, e.t, a)) at_a.passes.push_back({e.s, e.t});
    if (ob == 0 && strictly_within(e.s, e.t, b)) at_b.passes.push_back({e.s, e.t});
  }
  // A vertex end uses its precomputed cone (which already holds the edges it touches).
  auto end_free = [&](Cone& cone, Vec2 p, Vec2 q) {
    if (auto it = point_index_.find(p); it != point_index_.end())
      return direction_free(cones_[it->second], p, q);
    if (cone.passes.empty()) return true;
    finish(cone, p);
    return direction_free(cone, p, q);
  };
  if (!end_free(at_a, a, b) || !end_free(at_b, b, a)) return false;
  auto contact_free = [&](std::int32_t c) {
    const Vec2 v = points_[c];
    return direction_free(cones_[c], v, a) && direction_free(cones_[c], v, b);
  };
  for (int k = 0; k < n_contacts; ++k)
    if (!contact_free(contacts[k])) return false;
  for (std::int32_t c : more_contacts)
    if (!contact_free(c)) return false;
  return true;
}

Vec2 FreeSpace::nearest_free(Vec2 p) const {
  if (contains(p)) return p;
  double best = std::numeric_limits<double>::infinity();
  const Edge* best_edge = nullptr;
  Vec2 q{};
  double q_t = 0.0;
  for (const Edge& e : edges_) {
    double t;
    const Vec2 c = closest_on_segment(p, e.s, e.t, t);
    const double d = norm(c - p);
    if (d < best) {
      best = d;
      best_edge = &e;
      q = c;
      q_t = t;
    }
  }
  if (!best_edge) return p;
  if (q_t <= 0.0 || q_t >= 1.0 || contains(q)) return q;  // a vertex is exactly on the boundary
  // The foot of the perpendicular is rounded and may fall a hair outside free
  // space: step it off the edge, to the free (left) side, by a few ulps.
  const Vec2 d = best_edge->t - best_edge->s;
  const Vec2 left = (1.0 / norm(d)) * Vec2{-d.y, d.x};
  for (double step = 1e-13 * (1.0 + norm(q)); step < 1e-9; step *= 4.0) {
    const Vec2 r = q + step * left;
    if (contains(r)) return r;
  }
  // Cannot happen short of a boundary thinner than 1e-9 m; a vertex is always free.
  return norm(best_edge->s - p) <= norm(best_edge->t - p) ? best_edge->s : best_edge->t;
}

bool FreeSpace::is_bend_vertex(std::size_t i) const {
  const Cone& c = cones_[i];
  if (c.passes.size() != 1) return true;
  return exact_orient(c.passes[0].u, points_[i], c.passes[0].w) < 0;
}

bool FreeSpace::tangent_at(std::size_t i, Vec2 q) const {
  const Cone& c = cones_[i];
  if (c.passes.size() != 1) return true;
  const Vec2 v = points_[i];
  const int o1 = exact_orient(q, v, c.passes[0].u), o2 = exact_orient(q, v, c.passes[0].w);
  return o1 * o2 >= 0;
}

}  // namespace plumekit::planner
