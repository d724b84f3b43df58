#include "world/wind_fluctuation.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "core/geometry.hpp"

namespace plumekit::world {

namespace {

// The wall factor at each grid node ((nx+1) x (ny+1), row-major): 0 on the
// arena's boundary and at every corner of a solid cell, rising as a smoothstep
// of the distance from them to 1 at `layer` metres.
std::vector<double> wall_factor(const cfd::WindField& steady, double layer) {
  const GridShape& s = steady.shape();
  const int nx = s.nx, ny = s.ny;
  cv::Mat open(ny + 1, nx + 1, CV_8U, cv::Scalar(1));
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      bool wall = i == 0 || j == 0 || i == nx || j == ny;
      for (int dj = -1; !wall && dj <= 0; ++dj)
        for (int di = -1; !wall && di <= 0; ++di)
          wall = steady.solid(i + di, j + dj);
      if (wall) open.at<std::uint8_t>(j, i) = 0;
    }
  cv::Mat distance;
  cv::distanceTransform(open, distance, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  // Cells are square to within a rounding of the arena's size (GridShape::with_cell).
  const double h = 0.5 * (s.dx() + s.dy());
  std::vector<double> m(static_cast<std::size_t>(nx + 1) * (ny + 1));
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      const double t = std::min(1.0, distance.at<float>(j, i) * h / layer);
      m[static_cast<std::size_t>(j) * (nx + 1) + i] = t * t * (3.0 - 2.0 * t);
    }
  return m;
}

// The curl of the node streamfunction psi as a WindField: u = dpsi/dy on the
// vertical faces, v = -dpsi/dx on the horizontal ones, scaled by `scale`.
cfd::WindField curl(const cfd::WindField& steady, const std::vector<double>& psi, double scale) {
  const GridShape& s = steady.shape();
  const int nx = s.nx, ny = s.ny;
  auto node = [&](int i, int j) { return psi[static_cast<std::size_t>(j) * (nx + 1) + i]; };
  std::vector<double> face_u(static_cast<std::size_t>(nx + 1) * ny);
  std::vector<double> face_v(static_cast<std::size_t>(nx) * (ny + 1));
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i <= nx; ++i)
      face_u[static_cast<std::size_t>(j) * (nx + 1) + i] =
          scale * (node(i, j + 1) - node(i, j)) / s.dy();
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i < nx; ++i)
      face_v[static_cast<std::size_t>(j) * nx + i] =
          -scale * (node(i + 1, j) - node(i, j)) / s.dx();
  return cfd::WindField(s, std::move(face_u), std::move(face_v), std::vector<double>(s.size(), 0.0),
                        steady.solid_cells());
}

// The mean square speed per axis, (u^2 + v^2) / 2, over the cells whose four
// corners are past the wall layer (or over all fluid cells, when none is).
double mean_square_per_axis(const cfd::WindField& mode, const std::vector<double>& m) {
  const GridShape& s = mode.shape();
  double interior = 0.0, all = 0.0;
  long long n_interior = 0, n_all = 0;
  for (int j = 0; j < s.ny; ++j)
    for (int i = 0; i < s.nx; ++i) {
      if (mode.solid(i, j)) continue;
      const Vec2 w = mode.cell_velocity(i, j);
      const double e = 0.5 * (w.x * w.x + w.y * w.y);
      all += e;
      ++n_all;
      const std::size_t k = static_cast<std::size_t>(j) * (s.nx + 1) + i;
      if (std::min({m[k], m[k + 1], m[k + s.nx + 1], m[k + s.nx + 2]}) >= 1.0) {
        interior += e;
        ++n_interior;
      }
    }
  if (n_interior > 0) return interior / n_interior;
  return n_all > 0 ? all / n_all : 0.0;
}

}  // namespace

FluctuatingWind::FluctuatingWind(const cfd::WindField& steady, const FluctuationOptions& options,
                                 std::uint64_t seed)
    : steady_(steady), o_(options), rng_(seed) {
  const GridShape& s = steady.shape();
  wall_factor_ = wall_factor(steady, o_.wall_layer);
  constexpr int K = kModes;
  cell_modes_.assign(s.size() * 2 * K, 0.0f);
  for (int k = 0; k < K; ++k) {
    const double wavelength = o_.length_scale * (1.0 + uniform01(rng_));
    const double direction = kPi * uniform01(rng_);
    const double phase = 2.0 * kPi * uniform01(rng_);
    const double wavenumber = 2.0 * kPi / wavelength;
    waves_.push_back(
        {wavenumber * std::cos(direction), wavenumber * std::sin(direction), phase, 1.0});
    const cfd::WindField unscaled = mode(k);  // the curl is linear: scale its cells
    const double ms = mean_square_per_axis(unscaled, wall_factor_);
    const double scale = ms > 0.0 ? 1.0 / std::sqrt(ms) : 0.0;
    waves_.back().scale = scale;
    for (std::size_t c = 0; c < s.size(); ++c) {
      cell_modes_[c * 2 * K + k] = static_cast<float>(scale * unscaled.u()[c]);
      cell_modes_[c * 2 * K + K + k] = static_cast<float>(scale * unscaled.v()[c]);
    }
  }
  for (int k = 0; k < K; ++k)
    amplitude_.push_back(amplitude_sd() * normal_(rng_));
}

cfd::WindField FluctuatingWind::mode(int k) const {
  const GridShape& s = steady_.shape();
  const Wave& w = waves_[static_cast<std::size_t>(k)];
  std::vector<double> psi(wall_factor_.size());
  for (int j = 0; j <= s.ny; ++j)
    for (int i = 0; i <= s.nx; ++i) {
      const std::size_t n = static_cast<std::size_t>(j) * (s.nx + 1) + i;
      psi[n] = wall_factor_[n] * std::cos(w.kx * i * s.dx() + w.ky * j * s.dy() + w.phase);
    }
  return curl(steady_, psi, w.scale);
}

void FluctuatingWind::advance(double dt) {
  const double decay = std::exp(-dt / o_.time_scale);
  const double kick = amplitude_sd() * std::sqrt(1.0 - decay * decay);
  for (double& a : amplitude_)
    a = decay * a + kick * normal_(rng_);
}

Vec2 FluctuatingWind::at(Vec2 p, const double* amplitudes) const {
  // The steady flow's own corners and weights serve the modes too (solid
  // cells hold zero in every mode).
  cfd::CellCorners c;
  if (!steady_.corners(p, c)) return {};
  const double* w = c.weight;
  const std::size_t* cells = c.cell;
  const double *u0 = steady_.u().data(), *v0 = steady_.v().data();
  const Vec2 base{
      w[0] * u0[cells[0]] + w[1] * u0[cells[1]] + w[2] * u0[cells[2]] + w[3] * u0[cells[3]],
      w[0] * v0[cells[0]] + w[1] * v0[cells[1]] + w[2] * v0[cells[2]] + w[3] * v0[cells[3]]};
  // The corners first (independent lanes), then the amplitudes: short
  // dependency chains, as this runs for every filament at every step.
  constexpr int K = kModes;
  const float* m0 = &cell_modes_[cells[0] * 2 * K];
  const float* m1 = &cell_modes_[cells[1] * 2 * K];
  const float* m2 = &cell_modes_[cells[2] * 2 * K];
  const float* m3 = &cell_modes_[cells[3] * 2 * K];
  double mixed[2 * K];
  for (int k = 0; k < 2 * K; ++k)
    mixed[k] = (w[0] * double(m0[k]) + w[1] * double(m1[k])) +
               (w[2] * double(m2[k]) + w[3] * double(m3[k]));
  const double* a = amplitudes;
  const Vec2 d{((a[0] * mixed[0] + a[1] * mixed[1]) + (a[2] * mixed[2] + a[3] * mixed[3])) +
                   ((a[4] * mixed[4] + a[5] * mixed[5]) + (a[6] * mixed[6] + a[7] * mixed[7])),
               ((a[0] * mixed[8] + a[1] * mixed[9]) + (a[2] * mixed[10] + a[3] * mixed[11])) +
                   ((a[4] * mixed[12] + a[5] * mixed[13]) + (a[6] * mixed[14] + a[7] * mixed[15]))};
  static_assert(K == 8, "the sums above are written out for eight modes");
  return base + d;
}

}  // namespace plumekit::world
