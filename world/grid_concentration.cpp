// The concentration on a grid of sensors (a dataset's frames), fast engine: every filament's
// separable kernel, cut by the shadows of obstacle edges, summed tile by tile.
//
// Why tiles: a filament's window is a few dozen sensors wide, so a loop per filament and row
// spends more on starting short rows than on arithmetic. A tile of 8 x 8 sensors stays in
// registers while the filaments that reach it are added one after another, each as 8 row
// factors times 8 column factors. A sensor still adds its filaments in their order, one fused
// multiply-add each (zero where a shadow hides it or its window ends), as a loop per filament
// would: the sums do not depend on the tiles or on the threads' bands of rows.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "core/fast_math.hpp"
#include "world/filament_model.hpp"

namespace plumekit::world {

namespace {

constexpr int kTile = 8;  // sensors on a tile's side
// A tile row's sensors (GCC's vector extension: AVX-512 here, plain code elsewhere).
typedef double Lanes __attribute__((vector_size(kTile * sizeof(double))));

// By reference, never by value: a vector that size returned by value changes the calling ABI
// between builds with and without AVX-512 (GCC's -Wpsabi).
void load(const double* p, Lanes& v) {
  std::memcpy(&v, p, sizeof v);
}

void store(double* p, const Lanes& v) {
  std::memcpy(p, &v, sizeof v);
}

// Per 8 bits of hidden sensors, 1.0 in the lanes of those seen and 0.0 in the others: a factor
// times it is itself or zero, exactly.
struct SeenLanes {
  Lanes of[256];
  SeenLanes() {
    for (int bits = 0; bits < 256; ++bits)
      for (int c = 0; c < kTile; ++c)
        of[bits][c] = (bits >> c) & 1 ? 0.0 : 1.0;
  }
};
const SeenLanes kSeen;

// A filament's window (sensor columns i0..i1, rows j0..j1) on a band of rows, rounded out to
// tiles: tile columns ti0..ti1, tile rows tj0..tj1 of the band. Its kernel's factors are stored
// over those tiles, zero outside the window.
struct Footprint {
  int ti0, ti1, tj0, tj1;
  int ex, ey;  // offsets of its column and row factors
  // Offset of its hidden sensors' bits: per padded row, words of 64 bits (bit c: padded column
  // c); -1: none hidden.
  int masks = -1;
};

// The Gaussian kernel's 1-D factors exp(-(centre - at)^2 / r2) * amp for the centres of cells
// first..last of size `cell`, with plumekit's exp (a loop that vectorizes), at out[0..].
void kernel_factors(int first, int last, double cell, double at, double inv_r2, double amp,
                    double* out) {
  const int n = last - first + 1;
  for (int k = 0; k < n; ++k) {
    const double d = (first + k + 0.5) * cell - at;
    out[k] = amp * fast::exp_neg(-d * d * inv_r2);
  }
}

// GridTiles' working memory, kept by each thread from frame to frame: a dataset asks for
// thousands of frames, and memory allocated anew for each is memory the kernel maps and zeroes
// anew (a fifth of a dataset's time under AddressSanitizer, whose allocator returns large blocks
// to the system at once).
struct TileBuffers {
  std::vector<Footprint> footprints;
  std::vector<double> factors;
  std::vector<std::uint64_t> masks;
  std::vector<double> lo, hi;  // an edge's shadow on the window's rows
  std::vector<Edge> edges;
  std::vector<double> sums;  // the band's tiles
  std::vector<int> start, members, at;
};

// One frame's filaments on a band of sensor rows: their footprints, factors and shadows, then
// the tiles.
class GridTiles {
 public:
  GridTiles(const GridShape& shape, int row_lo, int row_hi, TileBuffers& buffers)
      : shape_(shape),
        row_lo_(row_lo),
        row_hi_(row_hi),
        tiles_x_((shape.nx + kTile - 1) / kTile),
        tiles_y_((row_hi - row_lo + 1 + kTile - 1) / kTile),
        footprints_(buffers.footprints),
        factors_(buffers.factors),
        masks_(buffers.masks),
        lo_(buffers.lo),
        hi_(buffers.hi),
        edges_(buffers.edges),
        b_(buffers) {
    footprints_.clear();
    factors_.clear();
    masks_.clear();
  }

  // The filament at f of `mass` and R^2 = r2, its kernel mass / (pi r2) exp(-d^2 / r2) out to
  // `reach`; `sight` (may be null) hides sensors behind obstacle edges.
  void add(Vec2 f, double r2, double reach, double mass, const LineOfSight* sight) {
    const double dx = shape_.dx(), dy = shape_.dy();
    const int i0 = std::max(0, static_cast<int>(std::ceil((f.x - reach) / dx - 0.5)));
    const int i1 = std::min(shape_.nx - 1, static_cast<int>(std::floor((f.x + reach) / dx - 0.5)));
    const int j0 = std::max(row_lo_, static_cast<int>(std::ceil((f.y - reach) / dy - 0.5)));
    const int j1 = std::min(row_hi_, static_cast<int>(std::floor((f.y + reach) / dy - 0.5)));
    if (i0 > i1 || j0 > j1) return;
    Footprint p;
    p.ti0 = i0 / kTile;
    p.ti1 = i1 / kTile;
    p.tj0 = (j0 - row_lo_) / kTile;
    p.tj1 = (j1 - row_lo_) / kTile;
    const int x0 = p.ti0 * kTile, y0 = row_lo_ + p.tj0 * kTile;  // the padded corner
    const int width = (p.ti1 - p.ti0 + 1) * kTile, height = (p.tj1 - p.tj0 + 1) * kTile;
    p.ex = static_cast<int>(factors_.size());
    p.ey = p.ex + width;
    factors_.resize(factors_.size() + width + height, 0.0);
    const double inv = 1.0 / r2;
    kernel_factors(i0, i1, dx, f.x, inv, 1.0, factors_.data() + p.ex + (i0 - x0));
    kernel_factors(j0, j1, dy, f.y, inv, mass * inv / kPi, factors_.data() + p.ey + (j0 - y0));
    if (sight) add_shadows(f, i0, i1, j0, j1, y0, height, sight, p);
    footprints_.push_back(p);
  }

  // Adds the filaments' concentrations to the band's rows of `out` (row-major, nx columns).
  void sum_into(std::vector<double>& out) const {
    const int band = row_hi_ - row_lo_ + 1;
    const int pitch = tiles_x_ * kTile;
    std::vector<double>& buf = b_.sums;
    buf.assign(static_cast<std::size_t>(pitch) * tiles_y_ * kTile, 0.0);
    for (int j = 0; j < band; ++j)
      std::copy_n(out.data() + static_cast<std::size_t>(row_lo_ + j) * shape_.nx, shape_.nx,
                  buf.data() + static_cast<std::size_t>(j) * pitch);
    tile_lists(b_.start);
    const std::vector<int>& start = b_.start;
    std::vector<int>& members = b_.members;
    members.resize(static_cast<std::size_t>(start.back()));
    std::vector<int>& at = b_.at;
    at.assign(start.begin(), start.end() - 1);
    for (std::size_t k = 0; k < footprints_.size(); ++k) {
      const Footprint& p = footprints_[k];
      for (int tj = p.tj0; tj <= p.tj1; ++tj)
        for (int ti = p.ti0; ti <= p.ti1; ++ti)
          members[static_cast<std::size_t>(at[tj * tiles_x_ + ti]++)] = static_cast<int>(k);
    }
    for (int tj = 0; tj < tiles_y_; ++tj)
      for (int ti = 0; ti < tiles_x_; ++ti) {
        const int t = tj * tiles_x_ + ti;
        sum_tile(ti, tj, members.data() + start[t], members.data() + start[t + 1],
                 buf.data() + static_cast<std::size_t>(tj) * kTile * pitch + ti * kTile, pitch);
      }
    for (int j = 0; j < band; ++j)
      std::copy_n(buf.data() + static_cast<std::size_t>(j) * pitch, shape_.nx,
                  out.data() + static_cast<std::size_t>(row_lo_ + j) * shape_.nx);
  }

 private:
  // Marks the window's sensors that obstacle edges facing f shadow, in bits by padded row.
  void add_shadows(Vec2 f, int i0, int i1, int j0, int j1, int y0, int height,
                   const LineOfSight* sight, Footprint& p) {
    const double dx = shape_.dx(), dy = shape_.dy();
    // The sensors' centres and the filament: every segment between them lies inside.
    const Vec2 lo{(i0 + 0.5) * dx, (j0 + 0.5) * dy}, hi{(i1 + 0.5) * dx, (j1 + 0.5) * dy};
    const Box window{{std::min(lo.x, f.x), std::min(lo.y, f.y)},
                     {std::max(hi.x, f.x), std::max(hi.y, f.y)}};
    edges_.clear();
    sight->facing_edges(f, window, edges_);
    const int x0 = p.ti0 * kTile;
    const int words = ((p.ti1 - p.ti0 + 1) * kTile + 63) / 64;
    for (const Edge& e : edges_) {
      const EdgeShadow shadow(f, e);
      // Rows and columns whose centres lie in the shadow, clamped in double (bounds may be
      // infinite).
      const double from_j = std::max<double>(j0, std::ceil(shadow.y_lo() / dy - 0.5));
      const double to_j = std::min<double>(j1, std::floor(shadow.y_hi() / dy - 0.5));
      if (from_j > to_j) continue;
      const int first = static_cast<int>(from_j), n = static_cast<int>(to_j) - first + 1;
      lo_.resize(static_cast<std::size_t>(n));
      hi_.resize(static_cast<std::size_t>(n));
      double* from = lo_.data();
      double* to = hi_.data();
      shadow.on_rows(first, n, dy, from, to);
      for (int r = 0; r < n; ++r) {  // the columns whose centres lie in the shadow
        from[r] = std::max<double>(i0, std::ceil(from[r] / dx - 0.5));
        to[r] = std::min<double>(i1, std::floor(to[r] / dx - 0.5));
      }
      for (int r = 0; r < n; ++r) {
        if (from[r] > to[r]) continue;
        if (p.masks < 0) {  // the first hidden sensor
          p.masks = static_cast<int>(masks_.size());
          masks_.resize(masks_.size() + static_cast<std::size_t>(height) * words, 0);
        }
        hide(masks_.data() + p.masks + static_cast<std::size_t>(first + r - y0) * words,
             static_cast<int>(from[r]) - x0, static_cast<int>(to[r]) - x0);
      }
    }
  }

  // Sets bits first..last of a row's words.
  static void hide(std::uint64_t* row, int first, int last) {
    for (int w = first / 64; w <= last / 64; ++w) {
      const int lo = w == first / 64 ? first % 64 : 0, hi = w == last / 64 ? last % 64 : 63;
      row[w] |= (~std::uint64_t{0} >> (63 - hi)) & (~std::uint64_t{0} << lo);
    }
  }

  // Bits c..c+7 of a row's words: the hidden sensors of the tile whose first column is c.
  static unsigned hidden_in(const std::uint64_t* row, int c) {
    return static_cast<unsigned>(row[c / 64] >> (c % 64)) & 0xFFu;
  }

  // Where each tile's filaments start in the members' list (the tiles row-major, one more
  // entry for the end).
  void tile_lists(std::vector<int>& start) const {
    start.assign(static_cast<std::size_t>(tiles_x_) * tiles_y_ + 1, 0);
    for (const Footprint& p : footprints_)
      for (int tj = p.tj0; tj <= p.tj1; ++tj)
        for (int ti = p.ti0; ti <= p.ti1; ++ti)
          ++start[static_cast<std::size_t>(tj * tiles_x_ + ti) + 1];
    for (std::size_t t = 1; t < start.size(); ++t)
      start[t] += start[t - 1];
  }

  // Adds the filaments `first`..`last` to the tile (ti, tj) at `tile` (rows `pitch` apart).
  void sum_tile(int ti, int tj, const int* first, const int* last, double* tile, int pitch) const {
    Lanes acc[kTile];
#pragma GCC unroll 8
    for (int r = 0; r < kTile; ++r)
      load(tile + r * pitch, acc[r]);
    for (const int* k = first; k != last; ++k) {
      const Footprint& p = footprints_[static_cast<std::size_t>(*k)];
      Lanes e;
      load(factors_.data() + p.ex + (ti - p.ti0) * kTile, e);
      const double* y = factors_.data() + p.ey + (tj - p.tj0) * kTile;
      if (p.masks < 0) {
#pragma GCC unroll 8
        for (int r = 0; r < kTile; ++r)
          acc[r] += y[r] * e;
        continue;
      }
      const int words = ((p.ti1 - p.ti0 + 1) * kTile + 63) / 64;
      const std::uint64_t* hidden = masks_.data() + p.masks + (tj - p.tj0) * kTile * words;
      const int c = (ti - p.ti0) * kTile;
#pragma GCC unroll 8
      for (int r = 0; r < kTile; ++r)
        acc[r] += y[r] * (e * kSeen.of[hidden_in(hidden + r * words, c)]);
    }
#pragma GCC unroll 8
    for (int r = 0; r < kTile; ++r)
      store(tile + r * pitch, acc[r]);
  }

  const GridShape& shape_;
  int row_lo_, row_hi_, tiles_x_, tiles_y_;
  std::vector<Footprint>& footprints_;
  std::vector<double>& factors_;
  std::vector<std::uint64_t>& masks_;
  std::vector<double>& lo_;  // an edge's shadow on the window's rows
  std::vector<double>& hi_;
  std::vector<Edge>& edges_;
  TileBuffers& b_;
};

}  // namespace

void FilamentSimulation::concentration(const GridShape& shape, std::vector<double>& out) const {
  // Threads take bands of rows; each sensor still sums its filaments in their order, so the
  // record does not depend on the thread count.
  const int parts = pool_ && x_.size() >= 256 ? std::min(pool_->size(), shape.ny) : 1;
  if (parts == 1) return concentration_rows(shape, 0, shape.ny - 1, out);
  pool_->parallel_for(static_cast<std::size_t>(parts), [&](std::size_t part) {
    const int p = static_cast<int>(part);
    concentration_rows(shape, shape.ny * p / parts, shape.ny * (p + 1) / parts - 1, out);
  });
}

void FilamentSimulation::concentration_rows(const GridShape& shape, int row_lo, int row_hi,
                                            std::vector<double>& out) const {
  if (o_.engine == PlumeEngine::V1) return concentration_rows_v1(shape, row_lo, row_hi, out);
  thread_local TileBuffers buffers;
  GridTiles tiles(shape, row_lo, row_hi, buffers);
  for (std::size_t k = 0; k < x_.size(); ++k)
    tiles.add({x_[k], y_[k]}, r2_[k], o_.cutoff * std::sqrt(r2_[k]), mass_, sight_.get());
  tiles.sum_into(out);
}

}  // namespace plumekit::world
