#include "cfd/staggered_grid.hpp"

#include <algorithm>

#include "core/rasterize.hpp"

namespace plumekit::cfd {

namespace {

bool covers_span(const Opening& o, Side side, double s) {
  return o.side == side && s >= o.from && s <= o.to;
}

// Inflow speed of the inlet profile at position s along its wall.
double inlet_speed(const Inlet& inlet, double s) {
  if (inlet.profile == Profile::Uniform) return inlet.speed;
  const double t = (s - inlet.from) / (inlet.to - inlet.from);
  return inlet.speed * 4.0 * t * (1.0 - t);
}

Side low_side(int c) {
  return c == 0 ? Side::Left : Side::Bottom;
}
Side high_side(int c) {
  return c == 0 ? Side::Right : Side::Top;
}
// Walls beyond the across direction of component c.
Side low_across_side(int c) {
  return c == 0 ? Side::Bottom : Side::Left;
}
Side high_across_side(int c) {
  return c == 0 ? Side::Top : Side::Right;
}

// Marks as solid the fluid cells that no path of fluid cells joins to an
// opening (or, in a closed box, to the first fluid cell): a pocket sealed by
// obstacles has no flow and no pressure level, and would leave the Newton
// matrix singular.
void seal_pockets(const Map& map, const GridShape& s, bool closed,
                  std::vector<std::uint8_t>& solid) {
  std::vector<char> reached(s.size(), 0);
  std::vector<int> queue;
  auto seed = [&](int i, int j) {
    const std::size_t k = s.index(i, j);
    if (!solid[k] && !reached[k]) reached[k] = 1, queue.push_back(static_cast<int>(k));
  };
  if (closed) {
    for (std::size_t k = 0; k < s.size() && queue.empty(); ++k)
      seed(static_cast<int>(k % s.nx), static_cast<int>(k / s.nx));
  } else {
    auto opening = [&](Side side, double at) {
      return wall_type(map, side, at, false) != WallType::Wall;
    };
    for (int j = 0; j < s.ny; ++j) {
      if (opening(Side::Left, (j + 0.5) * s.dy())) seed(0, j);
      if (opening(Side::Right, (j + 0.5) * s.dy())) seed(s.nx - 1, j);
    }
    for (int i = 0; i < s.nx; ++i) {
      if (opening(Side::Bottom, (i + 0.5) * s.dx())) seed(i, 0);
      if (opening(Side::Top, (i + 0.5) * s.dx())) seed(i, s.ny - 1);
    }
  }
  for (std::size_t q = 0; q < queue.size(); ++q) {
    const int i = queue[q] % s.nx, j = queue[q] / s.nx;
    if (i > 0) seed(i - 1, j);
    if (i + 1 < s.nx) seed(i + 1, j);
    if (j > 0) seed(i, j - 1);
    if (j + 1 < s.ny) seed(i, j + 1);
  }
  for (std::size_t k = 0; k < s.size(); ++k)
    if (!reached[k]) solid[k] = 1;
}

}  // namespace

WallType wall_type(const Map& map, Side side, double s, bool closed) {
  if (closed) return WallType::Wall;
  if (covers_span(map.inlet, side, s)) return WallType::Inlet;
  if (covers_span(map.outlet, side, s)) return WallType::Outlet;
  return WallType::Wall;
}

StaggeredGrid::StaggeredGrid(const Map& map, const GridShape& shape, const FlowOptions& options)
    : shape_(shape),
      solid_(rasterize_occupancy(map, shape).values),
      map_(&map),
      wall_speed_(options.wall_speed),
      closed_(options.closed) {
  seal_pockets(map, shape, closed_, solid_);
  for (int c = 0; c < 2; ++c) {
    kind_[c].assign(face_count(c), kFixed);
    fixed_[c].assign(face_count(c), 0.0);
    col_[c].assign(face_count(c), -1);
    for (int b = 0; b < n_across(c); ++b) {
      for (int a = 0; a <= n_along(c); ++a) {
        if (a == 0 || a == n_along(c)) {
          classify_boundary_face(map, c, a, b, options);
        } else if (!solid(c, a - 1, b) && !solid(c, a, b)) {
          kind_[c][face(c, a, b)] = kFree;
        }
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

void StaggeredGrid::classify_boundary_face(const Map& map, int c, int a, int b,
                                           const FlowOptions& options) {
  const bool high = a == n_along(c);
  const std::size_t f = face(c, a, b);
  if (solid(c, high ? a - 1 : a, b)) return;  // an obstacle against the wall
  const Side side = high ? high_side(c) : low_side(c);
  const double s = (b + 0.5) * h_across(c);
  switch (wall_type(map, side, s, options.closed)) {
    case WallType::Inlet:
      fixed_[c][f] = (high ? -1.0 : 1.0) * inlet_speed(map.inlet, s);
      break;
    case WallType::Outlet:
      kind_[c][f] = kOutflow;
      has_outflow_ = true;
      break;
    case WallType::Wall:
      break;  // no flow through a wall
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
  // Beyond the domain (only next to an outflow face, or two steps out), the
  // nearest face in that direction stands in: zero gradient.
  const int a2 = std::clamp(a + k, 0, n_along(c));
  return real_face(c, face(c, a2, b));
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
      // Both cells across are solid: an obstacle wall half a cell away.
      const Ref self = real_face(c, face(c, a, b));
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

Ref StaggeredGrid::pressure(int c, int b, int cell_along) const {
  Ref r;
  if (cell_along >= 0 && cell_along < n_along(c)) {
    r.col = p_col_[cell(c, cell_along, b)];
    r.scale = 1.0;
    return r;
  }
  // Beyond an outflow face: p = 0 on the boundary, so the ghost mirrors the inside.
  const int inside = cell_along < 0 ? 0 : n_along(c) - 1;
  r.col = p_col_[cell(c, inside, b)];
  r.scale = -1.0;
  return r;
}

}  // namespace plumekit::cfd
