// The fast engine's step (issue 45): the filaments as arrays, moved a block at a time; each
// filament's random walk drawn from counter-based normals keyed by the step and its release
// number (core/counter_random.hpp), so the draws do not depend on the order the filaments are
// moved in; the unsteady wind combined once per flow cell and step, where a filament needs it,
// instead of mode by mode at every filament.
#include <algorithm>
#include <cmath>

#include "core/counter_random.hpp"
#include "world/filament_model.hpp"

namespace plumekit::world {

namespace {

// Mixed into the plume's seed for each of the fast engine's random streams.
constexpr std::uint64_t kWalkStream = 0x77616c6b;     // "walk": the filaments' random walk
constexpr std::uint64_t kReleaseStream = 0x72656c73;  // "rels": release points on the disc
constexpr std::uint64_t kMeanderStream = 0x6d65616e;  // "mean": the uniform meander
// Filaments moved per block: the block's winds and normals stay in the first-level cache.
constexpr std::size_t kBlock = 256;

}  // namespace

Vec2 FilamentSimulation::release_point_fast(std::uint64_t serial) const {
  if (o_.source_radius <= 0.0) return source_;
  // Uniform over the disc's free part: redrawn where the disc overlaps a wall or an obstacle.
  const std::uint64_t key = splitmix64(seed_ ^ kReleaseStream);
  for (std::uint64_t attempt = 0; attempt < 100; ++attempt) {
    const double r = o_.source_radius * std::sqrt(counter_uniform(key, 256 * serial + 2 * attempt));
    double s, c;
    fast::sincos_turn(counter_uniform(key, 256 * serial + 2 * attempt + 1), s, c);
    const Vec2 p{source_.x + r * c, source_.y + r * s};
    if (map_.is_free(p)) return p;
  }
  return source_;
}

void FilamentSimulation::meander_fast(double dt) {
  if (fluctuation_) {
    fluctuation_->advance(dt);
    return;
  }
  // Ornstein-Uhlenbeck meander, exact update over dt.
  const double decay = std::exp(-dt / o_.meander_time);
  const double kick = o_.meander_speed * std::sqrt(1.0 - decay * decay);
  double zx, zy;
  counter_normals(splitmix64(seed_ ^ kMeanderStream), static_cast<std::uint64_t>(steps_), zx, zy);
  meander_.x = decay * meander_.x + kick * zx;
  meander_.y = decay * meander_.y + kick * zy;
}

void FilamentSimulation::winds_fast(std::size_t begin, std::size_t end) {
  const GridShape& s = wind_.shape();
  const double dx = s.dx(), dy = s.dy();
  const double *u0 = wind_.u().data(), *v0 = wind_.v().data();
  const std::vector<std::uint8_t>& solid = wind_.solid_cells();
  const long long stamp = steps_ + 1;
  // Bilinear between cell centres, constant beyond the outermost (GridShape::bilinear).
  auto axis = [](double g, int n, int& i0, int& i1, double& t) {
    g = std::clamp(g - 0.5, 0.0, static_cast<double>(n - 1));
    i0 = std::min(static_cast<int>(g), std::max(n - 2, 0));
    i1 = std::min(i0 + 1, n - 1);
    t = n > 1 ? g - i0 : 0.0;
  };
  for (std::size_t k = begin; k < end; ++k) {
    const double px = x_[k], py = y_[k];
    double wx = 0.0, wy = 0.0;
    const int ci = std::min(s.nx - 1, static_cast<int>(px / dx));
    const int cj = std::min(s.ny - 1, static_cast<int>(py / dy));
    // Zero outside the arena and in obstacle cells, as WindField::at.
    if (px >= 0.0 && px <= s.width && py >= 0.0 && py <= s.height && !solid[s.index(ci, cj)]) {
      int i0, i1, j0, j1;
      double tx, ty;
      axis(px / dx, s.nx, i0, i1, tx);
      axis(py / dy, s.ny, j0, j1, ty);
      const std::size_t cells[4] = {s.index(i0, j0), s.index(i1, j0), s.index(i0, j1),
                                    s.index(i1, j1)};
      const double w[4] = {(1 - tx) * (1 - ty), tx * (1 - ty), (1 - tx) * ty, tx * ty};
      if (fluctuation_) {
        for (const std::size_t c : cells)
          if (cell_stamp_[c] != stamp) {
            const Vec2 cw = fluctuation_->cell_wind(c);
            cell_u_[c] = cw.x;
            cell_v_[c] = cw.y;
            cell_stamp_[c] = stamp;
          }
        for (int c = 0; c < 4; ++c) {
          wx += w[c] * cell_u_[cells[c]];
          wy += w[c] * cell_v_[cells[c]];
        }
      } else {
        for (int c = 0; c < 4; ++c) {
          wx += w[c] * u0[cells[c]];
          wy += w[c] * v0[cells[c]];
        }
      }
    }
    if (!fluctuation_) {
      wx += meander_.x;
      wy += meander_.y;
    }
    wx_[k - begin] = wx;
    wy_[k - begin] = wy;
  }
}

void FilamentSimulation::step_fast() {
  const double dt = o_.dt;
  const double walk = o_.sigma_walk * std::sqrt(dt);
  meander_fast(dt);
  release_filaments(dt);
  const double growth = o_.growth * dt, max_r2 = o_.max_radius * o_.max_radius;
  // This step's key: filament `serial` takes pair `serial` of its stream.
  const std::uint64_t key =
      counter_bits(splitmix64(seed_ ^ kWalkStream), static_cast<std::uint64_t>(steps_));
  const std::size_t n = x_.size();
  wx_.resize(kBlock);
  wy_.resize(kBlock);
  double zx[kBlock], zy[kBlock];
  std::size_t kept = 0;
  for (std::size_t begin = 0; begin < n; begin += kBlock) {
    const std::size_t end = std::min(n, begin + kBlock), count = end - begin;
    winds_fast(begin, end);
    const std::uint64_t* serial = serial_.data() + begin;
    for (std::size_t k = 0; k < count; ++k)  // vectorized: no branch, no call
      counter_normals(key, serial[k], zx[k], zy[k]);
    for (std::size_t k = 0; k < count; ++k) {
      const std::size_t f = begin + k;
      const Vec2 from{x_[f], y_[f]};
      Vec2 p{from.x + dt * wx_[k] + walk * zx[k], from.y + dt * wy_[k] + walk * zy[k]};
      const Move move = settle(from, p);
      if (move == Move::Left) {
        ++summary_.left_through_outlet;
        continue;
      }
      if (move == Move::Rejected) {
        ++summary_.rejected_moves;
        p = from;
      }
      const double r2 = r2_[f] + growth;
      if (r2 > max_r2) {
        ++summary_.dropped_too_wide;
        continue;
      }
      x_[kept] = p.x;
      y_[kept] = p.y;
      r2_[kept] = r2;
      serial_[kept] = serial_[f];
      ++kept;
    }
  }
  x_.resize(kept);
  y_.resize(kept);
  r2_.resize(kept);
  serial_.resize(kept);
  time_ += dt;
}

}  // namespace plumekit::world
