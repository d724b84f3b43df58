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
