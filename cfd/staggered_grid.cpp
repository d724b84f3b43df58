#include "cfd/staggered_grid.hpp"

#include <algorithm>

#include "cfd/gap_closing.hpp"
#include "map/rasterize.hpp"

namespace plumekit::cfd {

namespace {

// Walls beyond the across direction of component c.
Side low_across_side(int c) {
  return c == 0 ? Side::Bottom : Side::Left;
}
Side high_across_side(int c) {
  return c == 0 ? Side::Top : Side::Right;
}

}  // namespace

WallType wall_type(const Map& map, Side side, double s, bool closed) {
  if (closed) return WallType::Wall;
  const int k = map.opening_on_wall(side, s);
  if (k < 0) return WallType::Wall;
  return map.openings[static_cast<std::size_t>(k)].is_inlet() ? WallType::Inlet : WallType::Outlet;
}

StaggeredGrid::StaggeredGrid(const Map& map, const GridShape& shape, const FlowOptions& options)
    : shape_(shape),
      solid_(rasterize_occupancy(map, shape).values),
      map_(&map),
      wall_speed_(options.wall_speed),
      closed_(options.closed) {
  // Gaps open in the map but narrower than a cell are closed (solid), so that
  // no one-cell channel depends on how the cells fall (gap_closing.hpp);
  // check_grid has reported them, or refused them under flow.strict_gaps.
  close_narrow_gaps(map, shape, solid_);
  seal_pockets();
  for (int c = 0; c < 2; ++c) {
    kind_[c].assign(face_count(c), kFixed);
    fixed_[c].assign(face_count(c), 0.0);
    col_[c].assign(face_count(c), -1);
    for (int b = 0; b < n_across(c); ++b) {
      for (int a = 0; a <= n_along(c); ++a) {
        const int side = fluid_side(c, a, b);
        if (side == 2)
          kind_[c][face(c, a, b)] = kFree;
        else if (side != 0)
          classify_boundary_face(c, a, b, side > 0);
      }
    }
  }
  // Number the unknowns: u faces, v faces, then the pressure of fluid cells.
  for (int c = 0; c < 2; ++c)
    for (std::size_t f = 0; f < face_count(c); ++f)
      if (kind_[c][f] != kFixed) col_[c][f] = unknowns_++;
  velocity_unknowns_ = unknowns_;
  p_col_.assign(shape.size(), -1);
  for (std::size_t k = 0; k < shape.size(); ++k)
    if (!solid_[k]) p_col_[k] = unknowns_++;
}

int StaggeredGrid::fluid_side(int c, int a, int b) const {
  const bool low = a > 0 && !solid(c, a - 1, b);
  const bool high = a < n_along(c) && !solid(c, a, b);
  return low && high ? 2 : high ? 1 : low ? -1 : 0;
}

int StaggeredGrid::opening_at(int c, int a, int b) const {
  if (closed_) return -1;
  return map_->opening_on_line(c == 0, a * h_along(c), 0.5 * h_along(c), (b + 0.5) * h_across(c));
}

// Marks as solid the fluid cells that no path of fluid cells joins to an
// outlet (or, in a closed box, to the first fluid cell): a pocket sealed by
// obstacles has no flow and no pressure level, and would leave the Newton
// matrix singular; so does a region that only an inlet opens (air comes in
// and cannot leave), as a real map's inlet along a whole wall can make.
void StaggeredGrid::seal_pockets() {
  const GridShape& s = shape_;
  std::vector<char> reached(s.size(), 0);
  std::vector<std::size_t> queue;
  auto seed = [&](std::size_t k) {
    if (!solid_[k] && !reached[k]) reached[k] = 1, queue.push_back(k);
  };
  if (closed_) {
    for (std::size_t k = 0; k < s.size() && queue.empty(); ++k)
      seed(k);
  } else {
    // The fluid cell beside each boundary face that lies on an outlet.
    for (int c = 0; c < 2; ++c)
      for (int b = 0; b < n_across(c); ++b)
        for (int a = 0; a <= n_along(c); ++a) {
          const int side = fluid_side(c, a, b);
          const int k = side == 1 || side == -1 ? opening_at(c, a, b) : -1;
          if (k >= 0 && !map_->openings[static_cast<std::size_t>(k)].is_inlet())
            seed(cell(c, side > 0 ? a : a - 1, b));
        }
  }
  for (std::size_t q = 0; q < queue.size(); ++q) {
    const int i = static_cast<int>(queue[q] % s.nx), j = static_cast<int>(queue[q] / s.nx);
    if (i > 0) seed(s.index(i - 1, j));
    if (i + 1 < s.nx) seed(s.index(i + 1, j));
    if (j > 0) seed(s.index(i, j - 1));
    if (j + 1 < s.ny) seed(s.index(i, j + 1));
  }
  for (std::size_t k = 0; k < s.size(); ++k)
    if (!reached[k]) solid_[k] = 1;
}

void StaggeredGrid::classify_boundary_face(int c, int a, int b, bool fluid_high) {
  const int k = opening_at(c, a, b);
  if (k < 0) return;  // a wall or an obstacle's side: no flow through it
  const Opening& o = map_->openings[static_cast<std::size_t>(k)];
  const std::size_t f = face(c, a, b);
  if (o.is_inlet()) {
    fixed_[c][f] = (fluid_high ? 1.0 : -1.0) * o.speed_at((b + 0.5) * h_across(c));
  } else {
    kind_[c][f] = kOutflow;
    has_outflow_ = true;
  }
}

Ref StaggeredGrid::real_face(int c, std::size_t f) const {
  Ref r;
  if (kind_[c][f] == kFixed) {
    r.offset = fixed_[c][f];
  } else {
    r.col = col_[c][f];
    r.scale = 1.0;
  }
  return r;
}

Ref StaggeredGrid::along(int c, int a, int b, int k) const {
  // Walk k faces along through fluid cells. Where the walk would leave the
  // fluid (only next to an outflow face, or two steps out), the last face
  // reached stands in: zero gradient.
  const int step = k > 0 ? 1 : -1;
  int at = a;
  for (int n = 0; n < std::abs(k); ++n) {
    const int between = step > 0 ? at : at - 1;
    if (between < 0 || between >= n_along(c) || solid(c, between, b)) break;
    at += step;
  }
  return real_face(c, face(c, at, b));
}

Ref StaggeredGrid::wall_ghost(int c, int a, int b, bool beyond_high) const {
  const Side side = beyond_high ? high_across_side(c) : low_across_side(c);
  const double s = a * h_along(c);
  const Ref self = real_face(c, face(c, a, b));
  Ref g;
  switch (wall_type(*map_, side, s, closed_)) {
    case WallType::Outlet:
      return self;  // zero gradient of the tangential velocity
    case WallType::Inlet:
      g.offset = -self.offset;  // no tangential inflow: the mean of face and ghost is 0
      break;
    case WallType::Wall:
      g.offset = 2.0 * wall_speed_[static_cast<int>(side)] - self.offset;
      break;
  }
  g.col = self.col;
  g.scale = -self.scale;
  return g;
}

Ref StaggeredGrid::across(int c, int a, int b, int k) const {
  const int step = k > 0 ? 1 : -1;
  const int b1 = b + step;
  // One step across: a domain wall, an obstacle's flat side, or a real face.
  Ref near;
  bool near_is_ghost = false;
  if (b1 < 0 || b1 >= n_across(c)) {
    near = wall_ghost(c, a, b, b1 >= n_across(c));
    near_is_ghost = true;
  } else {
    const bool low_solid = a > 0 && solid(c, a - 1, b1);
    const bool high_solid = a < n_along(c) && solid(c, a, b1);
    const bool beside_low = a > 0, beside_high = a < n_along(c);
    if ((!beside_low || low_solid) && (!beside_high || high_solid)) {
      // Both cells across are solid: an obstacle wall half a cell away, or an
      // outlet on an obstacle's edge (zero gradient of the tangential velocity).
      const Ref self = real_face(c, face(c, a, b));
      if (outlet_across(c, a, std::max(b, b1))) return self;
      near.col = self.col;
      near.scale = -self.scale;
      near.offset = -self.offset;
      near_is_ghost = true;
    } else {
      near = real_face(c, face(c, a, b1));
    }
  }
  if (k == step || near_is_ghost) return near;
  // Two steps across (for the limiter's far upwind value): the real face there
  // if there is one, else the near value again (the limiter then falls to upwind).
  const int b2 = b + 2 * step;
  if (b2 < 0 || b2 >= n_across(c)) return near;
  const bool low_solid = a > 0 && solid(c, a - 1, b2);
  const bool high_solid = a < n_along(c) && solid(c, a, b2);
  if (low_solid || high_solid) return near;
  return real_face(c, face(c, a, b2));
}

Ref StaggeredGrid::other(int c, int a_other, int b_other) const {
  const int o = 1 - c;
  // Outside the domain only beside an outflow face: zero gradient.
  b_other = std::clamp(b_other, 0, n_across(o) - 1);
  return real_face(o, face(o, a_other, b_other));
}

Ref StaggeredGrid::pressure(int c, int a, int b, bool high) const {
  const int inside = high ? a : a - 1;
  Ref r;
  if (inside >= 0 && inside < n_along(c) && !solid(c, inside, b)) {
    r.col = p_col_[cell(c, inside, b)];
    r.scale = 1.0;
    return r;
  }
  // Beyond an outflow face: p = 0 on the face, so the ghost mirrors the
  // fluid cell on its other side.
  r.col = p_col_[cell(c, high ? a - 1 : a, b)];
  r.scale = -1.0;
  return r;
}

bool StaggeredGrid::outlet_across(int c, int a, int b_line) const {
  if (closed_) return false;
  const int k =
      map_->opening_on_line(c == 1, b_line * h_across(c), 0.5 * h_across(c), a * h_along(c));
  return k >= 0 && !map_->openings[static_cast<std::size_t>(k)].is_inlet();
}

}  // namespace plumekit::cfd
