// The fast engine's step (issue 45): the filaments as arrays, moved a block at a time; each
// filament's random walk drawn from counter-based normals keyed by the step and its release
// number (core/counter_random.hpp), so the draws do not depend on the order the filaments are
// moved in; the unsteady wind combined once per flow cell and step, where a filament needs it,
// instead of mode by mode at every filament.
#include <algorithm>
#include <cmath>

#include "core/counter_random.hpp"
#include "core/thread_pool.hpp"
#include "world/filament_model.hpp"

namespace plumekit::world {

namespace {

// Mixed into the plume's seed for each of the fast engine's random streams.
constexpr std::uint64_t kWalkStream = 0x77616c6b;     // "walk": the filaments' random walk
constexpr std::uint64_t kReleaseStream = 0x72656c73;  // "rels": release points on the disc
constexpr std::uint64_t kMeanderStream = 0x6d65616e;  // "mean": the uniform meander
// Filaments moved per block: the block's winds and normals stay in the first-level cache.
constexpr std::size_t kBlock = 256;
// Threads pay from about this many filaments (a step of some 80 microseconds); below, waking
// them costs more than they save.
constexpr std::size_t kParallelFilaments = 4096;

// Each filament's lower-left cell centre and its bilinear weights (GridShape::bilinear: constant
// beyond the outermost centres); calm where WindField::at has no wind (outside the arena, in an
// obstacle cell).
struct CellWeights {
  int base[kBlock];
  double tx[kBlock], ty[kBlock];
  bool calm[kBlock];
};

void cell_weights(const cfd::WindField& wind, const double* x, const double* y, std::size_t count,
                  CellWeights& out) {
  const GridShape& s = wind.shape();
  const int nx = s.nx, ny = s.ny;
  const double inv_dx = 1.0 / s.dx(), inv_dy = 1.0 / s.dy();
  const std::uint8_t* solid = wind.solid_cells().data();
  for (std::size_t k = 0; k < count; ++k) {
    const double gx = std::clamp(x[k] * inv_dx - 0.5, 0.0, double(nx - 1));
    const double gy = std::clamp(y[k] * inv_dy - 0.5, 0.0, double(ny - 1));
    const int i0 = std::min(static_cast<int>(gx), std::max(nx - 2, 0));
    const int j0 = std::min(static_cast<int>(gy), std::max(ny - 2, 0));
    out.tx[k] = nx > 1 ? gx - i0 : 0.0;
    out.ty[k] = ny > 1 ? gy - j0 : 0.0;
    out.base[k] = j0 * nx + i0;
    const int ci = std::min(nx - 1, static_cast<int>(x[k] * inv_dx));
    const int cj = std::min(ny - 1, static_cast<int>(y[k] * inv_dy));
    const bool outside = !(x[k] >= 0.0 && x[k] <= s.width && y[k] >= 0.0 && y[k] <= s.height);
    out.calm[k] = outside || solid[static_cast<std::size_t>(cj) * nx + ci];
  }
}

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

void FilamentSimulation::winds_fast(std::size_t begin, std::size_t end, double* wx_out,
                                    double* wy_out) const {
  const GridShape& s = wind_.shape();
  const std::size_t count = end - begin;
  CellWeights cw;
  cell_weights(wind_, x_.data() + begin, y_.data() + begin, count, cw);
  const int step_x = s.nx > 1 ? 1 : 0, step_y = s.ny > 1 ? s.nx : 0;
  const int* base = cw.base;
  const double *tx = cw.tx, *ty = cw.ty;
  const bool* calm = cw.calm;
  const double *u = wind_.u().data(), *v = wind_.v().data();
  // The unsteady wind's modes in single precision, as they are stored: sixteen lanes.
  constexpr int K = FluctuatingWind::kModes;
  float a[2 * K] = {};
  if (fluctuation_)
    for (int j = 0; j < K; ++j)
      a[j] = a[K + j] = static_cast<float>(fluctuation_->amplitudes()[j]);
  const Vec2 swing = fluctuation_ ? Vec2{} : meander_;
  for (std::size_t k = 0; k < count; ++k) {
    const std::size_t c = calm[k] ? 0 : static_cast<std::size_t>(base[k]);
    const std::size_t c10 = c + step_x, c01 = c + step_y, c11 = c + step_x + step_y;
    const double w00 = (1 - tx[k]) * (1 - ty[k]), w10 = tx[k] * (1 - ty[k]),
                 w01 = (1 - tx[k]) * ty[k], w11 = tx[k] * ty[k];
    double wu = w00 * u[c] + w10 * u[c10] + w01 * u[c01] + w11 * u[c11];
    double wv = w00 * v[c] + w10 * v[c10] + w01 * v[c01] + w11 * v[c11];
    if (fluctuation_) {
      // The modes' bilinear mean, weighted by their amplitudes: sixteen lanes at once.
      const float *m00 = fluctuation_->cell_modes(c), *m10 = fluctuation_->cell_modes(c10),
                  *m01 = fluctuation_->cell_modes(c01), *m11 = fluctuation_->cell_modes(c11);
      const float f00 = static_cast<float>(w00), f10 = static_cast<float>(w10),
                  f01 = static_cast<float>(w01), f11 = static_cast<float>(w11);
      float p[2 * K];
      for (int j = 0; j < 2 * K; ++j)
        p[j] = a[j] * ((f00 * m00[j] + f10 * m10[j]) + (f01 * m01[j] + f11 * m11[j]));
      // Each half summed by halving (lanes j and j + 4, then j and j + 2, then the two left),
      // both halves at once: vector adds, no lane-by-lane sum.
      float h[8], g[4];
      for (int j = 0; j < 4; ++j) {
        h[j] = p[j] + p[j + 4];
        h[4 + j] = p[8 + j] + p[12 + j];
      }
      for (int j = 0; j < 2; ++j) {
        g[j] = h[j] + h[j + 2];
        g[2 + j] = h[4 + j] + h[6 + j];
      }
      wu += g[0] + g[1];
      wv += g[2] + g[3];
    }
    wx_out[k] = (calm[k] ? 0.0 : wu) + swing.x;
    wy_out[k] = (calm[k] ? 0.0 : wv) + swing.y;
  }
  static_assert(K == 8, "the sums above are written out for eight modes");
}

FilamentSimulation::Moved FilamentSimulation::move_fast(std::size_t begin, std::size_t end,
                                                        std::uint64_t key) {
  const double dt = o_.dt;
  const double walk = o_.sigma_walk * std::sqrt(dt);
  const double growth = o_.growth * dt, max_r2 = o_.max_radius * o_.max_radius;
  const double W = map_.width, H = map_.height;
  double wx[kBlock], wy[kBlock], zx[kBlock], zy[kBlock];
  Moved moved;
  std::size_t kept = begin;
  for (std::size_t first = begin; first < end; first += kBlock) {
    const std::size_t last = std::min(end, first + kBlock), count = last - first;
    winds_fast(first, last, wx, wy);
    const std::uint64_t* serial = serial_.data() + first;
    for (std::size_t k = 0; k < count; ++k)  // vectorized: no branch, no call
      counter_normals(key, serial[k], zx[k], zy[k]);
    for (std::size_t k = 0; k < count; ++k) {
      const std::size_t f = first + k;
      const Vec2 from{x_[f], y_[f]};
      Vec2 p{from.x + dt * wx[k] + walk * zx[k], from.y + dt * wy[k] + walk * zy[k]};
      // Most moves stay inside the arena, in a cell that decides without a polygon test.
      const bool plain = p.x > 0.0 && p.x < W && p.y > 0.0 && p.y < H && obstacles_.free(p);
      const Move move = plain ? Move::Kept : settle(from, p);
      if (place(f, kept, from, p, move, growth, max_r2, moved)) ++kept;
    }
  }
  moved.kept = kept - begin;
  return moved;
}

void FilamentSimulation::step_fast() {
  meander_fast(o_.dt);
  release_filaments(o_.dt);
  // This step's key: filament `serial` takes pair `serial` of its stream.
  const std::uint64_t key =
      counter_bits(splitmix64(seed_ ^ kWalkStream), static_cast<std::uint64_t>(steps_));
  const std::size_t n = x_.size();
  // Threads take equal runs of blocks; each filament's move depends on it alone, and the kept
  // ones close up in their order, so the plume does not depend on the thread count.
  const std::size_t parts =
      pool_ && n >= kParallelFilaments ? static_cast<std::size_t>(pool_->size()) : 1;
  const std::size_t blocks = (n + kBlock - 1) / kBlock;
  auto range = [&](std::size_t part) { return std::min(n, blocks * part / parts * kBlock); };
  std::vector<Moved> moved(parts);
  if (parts == 1)
    moved[0] = move_fast(0, n, key);
  else
    pool_->parallel_for(parts, [&](std::size_t part) {
      moved[part] = move_fast(range(part), range(part + 1), key);
    });
  std::size_t kept = 0;
  Moved all;
  for (std::size_t part = 0; part < parts; ++part) {
    const std::size_t from = range(part), count = moved[part].kept;
    if (from != kept) {
      std::copy(x_.begin() + from, x_.begin() + from + count, x_.begin() + kept);
      std::copy(y_.begin() + from, y_.begin() + from + count, y_.begin() + kept);
      std::copy(r2_.begin() + from, r2_.begin() + from + count, r2_.begin() + kept);
      std::copy(serial_.begin() + from, serial_.begin() + from + count, serial_.begin() + kept);
    }
    kept += count;
    all.left += moved[part].left;
    all.rejected += moved[part].rejected;
    all.dropped += moved[part].dropped;
  }
  close_up(kept, all);
  time_ += o_.dt;
}

}  // namespace plumekit::world
