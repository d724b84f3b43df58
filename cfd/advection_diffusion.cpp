#include "cfd/advection_diffusion.hpp"

#include <umfpack.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

#include <Eigen/SparseCore>

#include "core/error.hpp"
#include "core/option_check.hpp"
#include "core/resample.hpp"
#include "core/umfpack_lu.hpp"

namespace plumekit::cfd {

// The operator and its LU (plumekit::UmfpackLU: one BLAS policy for every UMFPACK
// call in plumekit). Solves are thread-safe: ste/ shares one model between runs.
struct AdvectionDiffusion::Lu {
  Eigen::SparseMatrix<double, Eigen::ColMajor, int> a;
  UmfpackLU lu;

  void factor() {
    lu.control(UMFPACK_IRSTEP) = 0;  // a direct LU of this operator needs no refinement
    lu.analyze(a);
    if (!lu.factorize(a))
      throw std::runtime_error("UMFPACK: the advection-diffusion operator is singular");
  }
  std::vector<double> solve(const std::vector<double>& b, bool transpose) const {
    std::vector<double> x(b.size(), 0.0);
    lu.solve_shared(a, b.data(), x.data(), transpose);
    return x;
  }
};

namespace {

// Patankar's hybrid scheme: the coefficient of the downstream-side neighbour
// for a face with outward volume flux F and diffusive conductance D. Central
// differencing while the cell Peclet number |F|/D <= 2, upwind beyond, so the
// operator stays an M-matrix (no negative concentrations).
double hybrid(double F, double D) {
  return std::max({-F, D - 0.5 * F, 0.0});
}

}  // namespace

const OptionTable<AdvectionDiffusionOptions>& advection_diffusion_option_table() {
  using O = AdvectionDiffusionOptions;
  static const OptionTable<O> table{
      "Advection-diffusion plume (cfd::AdvectionDiffusionOptions)",
      {{"plume.diffusivity", "--diffusivity", &O::diffusivity, positive(100.0, "m^2/s"),
        "Eddy diffusivity of the advection-diffusion plume (the dataset's; STE's physics "
        "model's), m^2/s"},
       {"plume.release_rate", "", &O::release_rate, positive(1e9, "concentration units * m^2/s"),
        "Release rate per metre of depth (concentration units * m^2/s)",
        "the default is {default}"},
       {"plume.decay_rate", "--decay-rate", &O::decay_rate, non_negative(100.0, "1/s"),
        "First-order decay rate of the gas, 1/s (0: no decay; STE's physics model takes the "
        "filament world's, whose filaments are dropped after a fixed lifetime: "
        "docs/validation.md, \"Floors\")",
        "0 means no decay"}}};
  return table;
}

void AdvectionDiffusionOptions::validate() const {
  plumekit::validate(advection_diffusion_option_table(), *this);
}

AdvectionDiffusion::AdvectionDiffusion(const cfd::WindField& wind,
                                       const AdvectionDiffusionOptions& options)
    : shape_(wind.shape()),
      options_(options),
      face_u_(wind.face_u()),
      face_v_(wind.face_v()),
      solid_(wind.solid_cells()),
      lu_(std::make_unique<Lu>()) {
  options.validate();
  const auto t0 = std::chrono::steady_clock::now();
  const int nx = shape_.nx, ny = shape_.ny;
  const double dx = shape_.dx(), dy = shape_.dy();
  unknown_.assign(shape_.size(), -1);
  for (std::size_t k = 0; k < shape_.size(); ++k) {
    if (solid_[k]) continue;
    unknown_[k] = static_cast<int>(cell_of_.size());
    cell_of_.push_back(static_cast<int>(k));
  }
  const int n = static_cast<int>(cell_of_.size());
  if (n == 0) throw InputError("advection-diffusion: the wind field has no free cells");
  summary_.nx = nx;
  summary_.ny = ny;
  summary_.unknowns = n;

  std::vector<Eigen::Triplet<double, int>> t;
  t.reserve(static_cast<std::size_t>(n) * 5);
  const double D = options.diffusivity;
  const double decay = options.decay_rate * dx * dy;  // the sink, integrated over a cell
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const int p = unknown_[shape_.index(i, j)];
      if (p < 0) continue;
      double diag = decay;
      // The four faces: outward flux F, conductance Dc, neighbour (or -1 at the arena edge).
      struct Face {
        double F, Dc;
        int ni, nj;
      };
      const Face faces[4] = {
          {face_u_[j * (nx + 1) + i + 1] * dy, D * dy / dx, i + 1, j},
          {-face_u_[j * (nx + 1) + i] * dy, D * dy / dx, i - 1, j},
          {face_v_[(j + 1) * nx + i] * dx, D * dx / dy, i, j + 1},
          {-face_v_[j * nx + i] * dx, D * dx / dy, i, j - 1},
      };
      for (const Face& f : faces) {
        const int q = shape_.contains(f.ni, f.nj) ? unknown_[shape_.index(f.ni, f.nj)] : -1;
        if (q >= 0) {
          const double a = hybrid(f.F, f.Dc);
          diag += a + f.F;
          t.emplace_back(p, q, -a);
          summary_.max_cell_peclet = std::max(summary_.max_cell_peclet, std::abs(f.F) / f.Dc);
        } else if (f.F > 0.0) {
          diag += f.F;  // outflow: upwind, zero gradient
        } else if (f.F < 0.0) {
          // Inflow of clean air: C = 0 on the face, half a cell away.
          diag += 2.0 * f.Dc;
        }
        // F == 0 on the arena's edge or an obstacle's: a wall, no flux. An
        // opening (the arena's or one on an obstacle's edge) has F != 0.
      }
      t.emplace_back(p, p, diag);
    }
  }
  lu_->a.resize(n, n);
  lu_->a.setFromTriplets(t.begin(), t.end());
  lu_->a.makeCompressed();
  summary_.nonzeros = lu_->a.nonZeros();
  lu_->factor();
  summary_.factor_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

AdvectionDiffusion::~AdvectionDiffusion() = default;

std::vector<std::pair<int, double>> AdvectionDiffusion::point_weights(Vec2 p) const {
  return free_bilinear_weights(shape_, solid_, p);
}

Grid<double> AdvectionDiffusion::solve(Vec2 source) const {
  const auto w = point_weights(source);
  if (w.empty())
    throw InputError("advection-diffusion: source " + to_string(source) +
                     " has no free cell of the flow grid near it: it is inside an obstacle, or in "
                     "a pocket of free space sealed off from the openings (no air reaches it)");
  std::vector<double> b(cell_of_.size(), 0.0);
  for (const auto& [k, weight] : w)
    b[unknown_[k]] += options_.release_rate * weight;
  const std::vector<double> x = lu_->solve(b, false);
  Grid<double> c(shape_, 0.0);
  for (std::size_t u = 0; u < x.size(); ++u)
    c.values[cell_of_[u]] = x[u];
  return c;
}

Grid<double> AdvectionDiffusion::adjoint(Vec2 sensor) const {
  const auto w = point_weights(sensor);
  Grid<double> g(shape_, 0.0);
  if (w.empty()) return g;
  std::vector<double> e(cell_of_.size(), 0.0);
  for (const auto& [k, weight] : w)
    e[unknown_[k]] += weight;
  const std::vector<double> x = lu_->solve(e, true);
  for (std::size_t u = 0; u < x.size(); ++u)
    g.values[cell_of_[u]] = options_.release_rate * x[u];
  return g;
}

double AdvectionDiffusion::face_flux(const Grid<double>& c, int i, int j) const {
  // +x flux through the face between (i-1, j) and (i, j).
  const int nx = shape_.nx;
  const double dx = shape_.dx(), dy = shape_.dy();
  const double F = face_u_[j * (nx + 1) + i] * dy;
  const double Dc = options_.diffusivity * dy / dx;
  const bool low = i > 0 && !solid_[shape_.index(i - 1, j)];
  const bool high = i < nx && !solid_[shape_.index(i, j)];
  if (low && high) {
    const double a = hybrid(F, Dc);
    return (a + F) * c(i - 1, j) - a * c(i, j);
  }
  // The free space's boundary, as in the operator: a wall (F = 0) passes
  // nothing; an opening lets out upwind and lets in C = 0 half a cell away.
  if (F == 0.0 || (!low && !high)) return 0.0;
  if (high) return F > 0.0 ? -2.0 * Dc * c(i, j) : F * c(i, j);
  return F > 0.0 ? F * c(i - 1, j) : 2.0 * Dc * c(i - 1, j);
}

double AdvectionDiffusion::flux_through_column(const Grid<double>& c, int i) const {
  double total = 0.0;
  for (int j = 0; j < shape_.ny; ++j)
    total += face_flux(c, i, j);
  return total;
}

}  // namespace plumekit::cfd
