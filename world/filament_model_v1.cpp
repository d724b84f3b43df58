// The V1 engine: the filament world before issue 45, bit for bit (--world faithful-v1, thesis-v1,
// neumann-v1). Kept for one release so that published numbers can be reproduced; it goes in the
// release after (docs/world.md, "Worlds"). One mt19937_64 draws everything in the filaments'
// order, the unsteady wind is read mode by mode at each filament, and a sensor scans every
// filament.
#include <algorithm>
#include <cmath>

#include "world/filament_model.hpp"

namespace plumekit::world {

std::vector<std::uint8_t> clear_cells_v1(const Map& map, const GridShape& s) {
  // Cells no obstacle reaches need no polygon test: the common case, and the
  // exact test stays for cells an obstacle edge crosses.
  std::vector<std::uint8_t> clear(s.size(), 1);
  const double half_diagonal = 0.5 * std::hypot(s.dx(), s.dy()) * (1.0 + 1e-9);
  for (int j = 0; j < s.ny; ++j)
    for (int i = 0; i < s.nx; ++i) {
      const Vec2 c = s.centre(i, j);
      bool free = map.obstacle_at(c) < 0;
      for (const Polygon& poly : map.obstacles) {
        for (std::size_t k = 0; free && k < poly.size(); ++k)
          if (distance_to_segment(c, poly[k], poly[(k + 1) % poly.size()]) <= half_diagonal)
            free = false;
        if (!free) break;
      }
      clear[s.index(i, j)] = free;
    }
  return clear;
}

namespace {

// A filament's kernel window: sensor columns i0..i1, rows j0..j1 of a grid of cell dx x dy.
struct Window {
  int i0, i1, j0, j1;
  double dx, dy;
};

// Zeroes, in the window's row-major mask, the sensors in `shadow`; a row's
// mask is set to ones the first time a shadow reaches it (masked[row] = 1).
void shade(const EdgeShadow& shadow, const Window& w, std::vector<double>& mask,
           std::vector<std::uint8_t>& masked) {
  const std::size_t width = static_cast<std::size_t>(w.i1 - w.i0 + 1);
  // Rows and columns whose centres lie in the shadow, clamped in double (bounds may be infinite).
  const double from_j = std::max<double>(w.j0, std::ceil(shadow.y_lo() / w.dy - 0.5));
  const double to_j = std::min<double>(w.j1, std::floor(shadow.y_hi() / w.dy - 0.5));
  if (from_j > to_j) return;
  for (int j = static_cast<int>(from_j); j <= static_cast<int>(to_j); ++j) {
    double lo, hi;
    if (!shadow.on_row((j + 0.5) * w.dy, lo, hi)) continue;
    const double from_i = std::max<double>(w.i0, std::ceil(lo / w.dx - 0.5));
    const double to_i = std::min<double>(w.i1, std::floor(hi / w.dx - 0.5));
    if (from_i > to_i) continue;
    double* row = mask.data() + (j - w.j0) * width;
    if (!masked[j - w.j0]) std::fill(row, row + width, 1.0);
    masked[j - w.j0] = 1;
    std::fill(row + (static_cast<int>(from_i) - w.i0), row + (static_cast<int>(to_i) - w.i0 + 1),
              0.0);
  }
}

// The Gaussian kernel's 1-D factors exp(-(centre - at)^2 / r2) * amp for the centres of cells
// first..last of size `cell`, with libm's exp.
void kernel_factors_v1(int first, int last, double cell, double at, double inv_r2, double amp,
                       std::vector<double>& out) {
  out.resize(static_cast<std::size_t>(last - first + 1));
  double* o = out.data();
  for (int i = first; i <= last; ++i) {
    const double d = (i + 0.5) * cell - at;
    o[i - first] = amp * std::exp(-d * d * inv_r2);
  }
}

}  // namespace

void FilamentSimulation::concentration_rows_v1(const GridShape& shape, int row_lo, int row_hi,
                                               std::vector<double>& out) const {
  const double dx = shape.dx(), dy = shape.dy();
  std::vector<double> ex, ey, mask;
  std::vector<std::uint8_t> masked;  // per window row: some sensor in it is hidden
  std::vector<Edge> edges;
  for (std::size_t k = 0; k < x_.size(); ++k) {
    const Vec2 f{x_[k], y_[k]};
    const double r = o_.cutoff * std::sqrt(r2_[k]);
    const int i0 = std::max(0, static_cast<int>(std::ceil((f.x - r) / dx - 0.5)));
    const int i1 = std::min(shape.nx - 1, static_cast<int>(std::floor((f.x + r) / dx - 0.5)));
    const int j0 = std::max(row_lo, static_cast<int>(std::ceil((f.y - r) / dy - 0.5)));
    const int j1 = std::min(row_hi, static_cast<int>(std::floor((f.y + r) / dy - 0.5)));
    if (i0 > i1 || j0 > j1) continue;
    const double inv = 1.0 / r2_[k];
    // The kernel is separable: two short 1-D tables, then an outer product.
    kernel_factors_v1(i0, i1, dx, f.x, inv, 1.0, ex);
    kernel_factors_v1(j0, j1, dy, f.y, inv, mass_ * inv / kPi, ey);
    // With occlusion, mark the window's rows that some obstacle edge shadows.
    masked.assign(ey.size(), 0);
    if (sight_) {
      // The sensors' centres and the filament: every segment between them lies inside.
      const Vec2 lo{(i0 + 0.5) * dx, (j0 + 0.5) * dy}, hi{(i1 + 0.5) * dx, (j1 + 0.5) * dy};
      const Box window{{std::min(lo.x, f.x), std::min(lo.y, f.y)},
                       {std::max(hi.x, f.x), std::max(hi.y, f.y)}};
      edges.clear();
      sight_->facing_edges(f, window, edges);
      mask.resize(ex.size() * ey.size());
      for (const Edge& e : edges)
        shade(EdgeShadow(f, e), {i0, i1, j0, j1, dx, dy}, mask, masked);
    }
    for (int j = j0; j <= j1; ++j) {
      double* row = out.data() + static_cast<std::size_t>(j) * shape.nx;
      const double a = ey[j - j0];
      if (!masked[j - j0]) {
        for (int i = i0; i <= i1; ++i)
          row[i] += a * ex[i - i0];
        continue;
      }
      const double* row_mask = mask.data() + (j - j0) * ex.size();
      for (int i = i0; i <= i1; ++i)
        row[i] += a * ex[i - i0] * row_mask[i - i0];
    }
  }
}

Vec2 FilamentSimulation::release_point_v1() {
  if (o_.source_radius <= 0.0) return source_;
  // Uniform over the disc's free part: redrawn where the disc overlaps a wall or an obstacle.
  for (int attempt = 0; attempt < 100; ++attempt) {
    const double r = o_.source_radius * std::sqrt(uniform01(rng_));
    const double a = 2.0 * kPi * uniform01(rng_);
    const Vec2 p{source_.x + r * std::cos(a), source_.y + r * std::sin(a)};
    if (map_.is_free(p)) return p;
  }
  return source_;
}

void FilamentSimulation::advance_meander_v1(double dt) {
  if (fluctuation_) {
    fluctuation_->advance(dt);
  } else {
    // Ornstein-Uhlenbeck meander, exact update over dt.
    const double decay = std::exp(-dt / o_.meander_time);
    const double kick = o_.meander_speed * std::sqrt(1.0 - decay * decay);
    meander_.x = decay * meander_.x + kick * normal_(rng_);
    meander_.y = decay * meander_.y + kick * normal_(rng_);
  }
}

void FilamentSimulation::step_v1() {
  const double dt = o_.dt;
  const double walk = o_.sigma_walk * std::sqrt(dt);
  advance_meander_v1(dt);
  release_filaments(dt);
  const double growth = o_.growth * dt, max_r2 = o_.max_radius * o_.max_radius;
  // The kept filaments close up in place, in their order: the random draws stay in that order.
  Moved fates;
  for (std::size_t k = 0; k < x_.size(); ++k) {
    const Vec2 from{x_[k], y_[k]};
    const Vec2 w = wind_at(from);
    Vec2 p = from + dt * w;
    p.x += walk * normal_(rng_);
    p.y += walk * normal_(rng_);
    const Move move = settle(from, p);
    if (place(k, fates.kept, from, p, move, growth, max_r2, fates)) ++fates.kept;
  }
  close_up(fates.kept, fates);
  time_ += dt;
}

double PlumeFrame::concentration_v1(Vec2 p) const {
  // The same kernel and cutoff as concentration(), at one point (a square of
  // half-side cutoff * R, as there). With occlusion, the edges that face the
  // sensor within any filament's reach decide which filaments it sees.
  const FilamentOptions& o = sim_->o_;
  std::vector<Edge> edges;
  if (sim_->sight_) {
    const double reach = o.cutoff * o.max_radius;
    sim_->sight_->facing_edges(p, {{p.x - reach, p.y - reach}, {p.x + reach, p.y + reach}}, edges);
  }
  double c = 0.0;
  for (std::size_t k = 0; k < x_.size(); ++k) {
    const Vec2 f{x_[k], y_[k]};
    const double dx = p.x - f.x, dy = p.y - f.y;
    const double reach = o.cutoff * o.cutoff * r2_[k];
    if (dx * dx > reach || dy * dy > reach) continue;
    if (std::any_of(edges.begin(), edges.end(), [&](const Edge& e) { return hides(p, e, f); }))
      continue;
    c += std::exp(-(dx * dx + dy * dy) / r2_[k]) / r2_[k];
  }
  return c * sim_->mass_ / kPi;
}

}  // namespace plumekit::world
