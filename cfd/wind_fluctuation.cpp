#include "cfd/wind_fluctuation.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "core/geometry.hpp"

namespace plumekit::cfd {

namespace {

// The wall factor at each grid node ((nx+1) x (ny+1), row-major): 0 on the
// arena's boundary and at every corner of a solid cell, rising as a smoothstep
// of the distance from them to 1 at `layer` metres.
std::vector<double> wall_factor(const WindField& steady, double layer) {
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
WindField curl(const WindField& steady, const std::vector<double>& psi, double scale) {
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
  return WindField(s, std::move(face_u), std::move(face_v), std::vector<double>(s.size(), 0.0),
                   steady.solid_cells());
}

// The mean square speed per axis, (u^2 + v^2) / 2, over the cells whose four
// corners are past the wall layer (or over all fluid cells, when none is).
double mean_square_per_axis(const WindField& mode, const std::vector<double>& m) {
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

FluctuatingWind::FluctuatingWind(const WindField& steady, const FluctuationOptions& options,
                                 std::uint64_t seed)
    : steady_(steady), o_(options), rng_(seed) {
  const GridShape& s = steady.shape();
  const std::vector<double> m = wall_factor(steady, o_.wall_layer);
  std::vector<double> psi(m.size());
  for (int k = 0; k < o_.modes; ++k) {
    const double wavelength = o_.length_scale * (1.0 + uniform01(rng_));
    const double direction = kPi * uniform01(rng_);
    const double phase = 2.0 * kPi * uniform01(rng_);
    const double kx = 2.0 * kPi / wavelength * std::cos(direction);
    const double ky = 2.0 * kPi / wavelength * std::sin(direction);
    for (int j = 0; j <= s.ny; ++j)
      for (int i = 0; i <= s.nx; ++i) {
        const std::size_t n = static_cast<std::size_t>(j) * (s.nx + 1) + i;
        psi[n] = m[n] * std::cos(kx * i * s.dx() + ky * j * s.dy() + phase);
      }
    const double ms = mean_square_per_axis(curl(steady, psi, 1.0), m);
    modes_.push_back(curl(steady, psi, ms > 0.0 ? 1.0 / std::sqrt(ms) : 0.0));
  }
  // Independent modes of unit strength: K of them with std sigma / sqrt(K)
  // give std sigma per axis.
  const double sd = o_.modes > 0 ? o_.intensity / std::sqrt(o_.modes) : 0.0;
  for (int k = 0; k < o_.modes; ++k)
    amplitude_.push_back(sd * normal_(rng_));
  update_cells();
}

void FluctuatingWind::advance(double dt) {
  const double decay = std::exp(-dt / o_.time_scale);
  const double kick =
      (o_.modes > 0 ? o_.intensity / std::sqrt(o_.modes) : 0.0) * std::sqrt(1.0 - decay * decay);
  for (double& a : amplitude_)
    a = decay * a + kick * normal_(rng_);
  update_cells();
}

void FluctuatingWind::update_cells() {
  u_ = steady_.u();
  v_ = steady_.v();
  const std::size_t n = u_.size();
  for (std::size_t k = 0; k < modes_.size(); ++k) {
    const double a = amplitude_[k];
    const double* mu = modes_[k].u().data();
    const double* mv = modes_[k].v().data();
    for (std::size_t c = 0; c < n; ++c) {
      u_[c] += a * mu[c];
      v_[c] += a * mv[c];
    }
  }
}

Vec2 FluctuatingWind::at(Vec2 p) const {
  return sample_cell_velocity(steady_.shape(), steady_.solid_cells(), u_, v_, p);
}

}  // namespace plumekit::cfd
