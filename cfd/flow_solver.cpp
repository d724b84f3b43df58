#include "cfd/flow_solver.hpp"

#include <umfpack.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>
#include <sstream>

#include "cfd/anderson.hpp"
#include "cfd/diagonal_pairing.hpp"
#include "cfd/eddy_viscosity.hpp"
#include "cfd/grid_check.hpp"
#include "cfd/navier_stokes.hpp"
#include "cfd/nullspace_solver.hpp"
#include "cfd/staggered_grid.hpp"
#include "cfd/umfpack_lu.hpp"
#include "core/option_check.hpp"

namespace plumekit::cfd {

const char* to_string(Turbulence t) {
  return t == Turbulence::None ? "none" : "mixing-length";
}

const char* to_string(Convection c) {
  switch (c) {
    case Convection::Upwind:
      return "upwind";
    case Convection::Central:
      return "central";
    case Convection::VanLeer:
      return "vanleer";
  }
  return "?";
}

std::string FlowSummary::history_text() const {
  std::ostringstream s;
  s << "  iter   momentum    continuity  cfl\n";
  for (std::size_t k = 0; k < history.size(); ++k) {
    char line[96];
    std::snprintf(line, sizeof line, "  %4zu   %.3e   %.3e   %.1e\n", k, history[k].momentum,
                  history[k].continuity, history[k].cfl);
    s << line;
  }
  return s.str();
}

namespace {

// What to change when Newton does not converge. At a high Reynolds number the
// flow may have no steady state on this grid (a larger viscosity, a finer
// cell or upwinding help); at a low one the viscous terms dwarf the residual's
// scale, so round-off alone keeps it above the tolerance (a smaller viscosity
// or a looser tolerance help).
std::string convergence_advice(double reynolds, const FlowOptions& o) {
  if (reynolds < 1.0)
    return "The flow is dominated by viscosity: try a smaller flow.nu (the default is 0.01 m^2/s) "
           "or a larger flow.tolerance (now " +
           compact(o.tolerance) + ").";
  std::string advice = "Try a larger flow.nu, a finer flow.cell";
  if (o.convection != Convection::Upwind) advice += ", or upwind convection (flow.convection)";
  return advice + ".";
}

// Reference scales for the normalised residuals.
struct Scales {
  double speed = 1.0;
  double length = 1.0;
};

Scales reference_scales(const Map& map, const FlowOptions& o) {
  Scales s;
  s.length = std::min(map.width, map.height);
  double u = o.closed ? 0.0 : map.inlet.speed;
  for (double w : o.wall_speed)
    u = std::max(u, std::abs(w));
  s.speed = u > 0.0 ? u : 1.0;
  return s;
}

}  // namespace

namespace {

// Initial unknowns from a coarser solution: velocities sampled at the fine
// faces, pressure from the coarse cell that holds each fine cell centre.
Eigen::VectorXd interpolate(const StaggeredGrid& grid, const WindField& coarse) {
  Eigen::VectorXd x = Eigen::VectorXd::Zero(grid.unknowns());
  const GridShape& s = grid.shape();
  for (int c = 0; c < 2; ++c)
    for (int b = 0; b < grid.n_across(c); ++b)
      for (int a = 0; a <= grid.n_along(c); ++a) {
        const int col = grid.column(c, grid.face(c, a, b));
        if (col < 0) continue;
        const Vec2 at =
            c == 0 ? Vec2{a * s.dx(), (b + 0.5) * s.dy()} : Vec2{(b + 0.5) * s.dx(), a * s.dy()};
        const Vec2 w = coarse.at(at);
        x[col] = c == 0 ? w.x : w.y;
      }
  const GridShape& cs = coarse.shape();
  for (int j = 0; j < s.ny; ++j)
    for (int i = 0; i < s.nx; ++i) {
      const int col = grid.pressure_column(s.index(i, j));
      if (col < 0) continue;
      const Vec2 c = s.centre(i, j);
      const int ci = std::min(cs.nx - 1, static_cast<int>(c.x / cs.dx()));
      const int cj = std::min(cs.ny - 1, static_cast<int>(c.y / cs.dy()));
      x[col] = coarse.cell_pressure(ci, cj);
    }
  return x;
}

// Grids with fewer cells than this across are solved from rest.
constexpr int kMinSequencedCells = 25;
// A factorization is kept for further (chord) steps while each step still
// cuts the merit by this factor; a chord step costs one pair of triangular
// solves, a fresh factorization 25 of them on the 5 cm benchmark grid, so
// even slow chord steps are worth taking.
constexpr double kChordRatio = 0.8;
// With the mixing-length closure the equations change at every iteration (the
// lagged eddy viscosity), so the history is dropped and plain chord steps
// must halve the merit, or the run needs far more iterations.
constexpr double kChordRatioLagged = 0.5;
// Chord steps are Anderson-accelerated over this many previous steps.
constexpr int kAndersonDepth = 4;
// Coarse grids only provide a start; their own discretisation error is far
// above this.
constexpr double kCoarseTolerance = 1e-4;

// The coarse flow to start from, if a twice-coarser grid is worth solving and
// can represent the map; otherwise none (Newton starts from rest).
std::optional<WindField> coarse_start(const Map& map, const FlowOptions& options,
                                      const GridShape& shape) {
  if (!options.sequencing || std::min(shape.nx, shape.ny) < kMinSequencedCells) return std::nullopt;
  FlowOptions coarse = options;
  coarse.cell = 2.0 * std::max(shape.dx(), shape.dy());
  // A start needs no more accuracy than the coarse grid's own discretisation error.
  coarse.tolerance = std::max(options.tolerance, kCoarseTolerance);
  // The coarsest grid starts from rest, where first-order upwinding makes
  // Newton converge in a few steps; its flow is only a start for the next grid.
  const GridShape cs = GridShape::with_cell(map.width, map.height, coarse.cell);
  if (std::min(cs.nx, cs.ny) < kMinSequencedCells) coarse.convection = Convection::Upwind;
  coarse.on_iteration = nullptr;
  try {
    return solve(map, coarse).wind;
  } catch (const InputError&) {
    return std::nullopt;  // the coarse grid closes a gap, or does not converge
  }
}

}  // namespace

FlowResult solve(const Map& map, const FlowOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  options.validate();
  check_grid_size(map, options);  // before any grid is made: the size and the memory
  const GridShape shape = GridShape::with_cell(map.width, map.height, options.cell);
  check_grid(map, shape, options);

  const StaggeredGrid grid(map, shape, options);
  NavierStokes equations(grid, options.convection);
  const int n = grid.unknowns(), n_mom = grid.velocity_unknowns();
  const Scales scales = reference_scales(map, options);
  const int max_iterations = options.max_iterations > 0 ? options.max_iterations
                             : options.turbulence == Turbulence::MixingLength ? 300
                                                                              : 100;
  EddyViscosity eddy(grid, options);

  FlowSummary summary;
  summary.nx = shape.nx;
  summary.ny = shape.ny;
  summary.dx = shape.dx();
  summary.dy = shape.dy();
  summary.nu = options.nu;
  summary.turbulence = options.turbulence;
  summary.convection = options.convection;
  summary.tolerance = options.tolerance;

  const auto t_coarse = std::chrono::steady_clock::now();
  const std::optional<WindField> coarse = coarse_start(map, options, shape);
  summary.coarse_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t_coarse).count();
  Eigen::VectorXd x = coarse ? interpolate(grid, *coarse) : Eigen::VectorXd::Zero(n);
  Eigen::VectorXd f(n), f_trial(n), step(n), rhs(n);
  std::vector<double> nu_cell(shape.size(), options.nu);
  equations.set_viscosity(nu_cell);

  auto norms = [&](const Eigen::VectorXd& r) {
    IterationRecord rec;
    rec.momentum =
        r.head(n_mom).lpNorm<Eigen::Infinity>() * scales.length / (scales.speed * scales.speed);
    rec.continuity = r.tail(n - n_mom).lpNorm<Eigen::Infinity>() * scales.length / scales.speed;
    return rec;
  };
  // Merit for globalisation: the RMS of the residual scaled like the norms.
  Eigen::VectorXd weight(n);
  weight.head(n_mom).setConstant(scales.length / (scales.speed * scales.speed));
  weight.tail(n - n_mom).setConstant(scales.length / scales.speed);
  auto merit = [&](const Eigen::VectorXd& r) {
    return std::sqrt(r.cwiseProduct(weight).squaredNorm() / n);
  };

  UmfpackLU lu;
  // No iterative refinement: Newton's next residual does that job, and each
  // refinement step would cost another pair of triangular solves.
  lu.control(UMFPACK_IRSTEP) = 0;
  // The rows are paired so that the matrix has a full diagonal, which lets
  // UMFPACK order A + A' and pivot on the diagonal (diagonal_pairing.hpp).
  lu.control(UMFPACK_STRATEGY) = UMFPACK_STRATEGY_SYMMETRIC;
  // Made with the first Jacobian: the nullspace solver where it applies,
  // else the coupled matrix with its rows paired.
  std::optional<NullSpaceSolver> nullspace;
  std::optional<DiagonalPairing> pairing;
  // Each step solves (J + I/dtau) dx = -F, dtau = cfl h / U: a huge cfl is
  // Newton, a small one a damped implicit time step. The step is then cut
  // back until the merit falls (backtracking). cfl grows with the merit's
  // fall after each success (SER) and shrinks when no cut-back helps.
  const double h = std::min(shape.dx(), shape.dy());
  double cfl = 1e6;
  bool refactor = true;

  const double reynolds = scales.speed * scales.length / options.nu;
  auto fail = [&](const std::string& why) {
    summary.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::ostringstream msg;
    msg << "flow solver: " << why << " after " << summary.iterations << " iterations on a "
        << shape.nx << " x " << shape.ny << " grid (nu " << options.nu << " m^2/s, "
        << to_string(options.convection) << " convection, Reynolds number " << compact(reynolds)
        << "). " << convergence_advice(reynolds, options) << "\nResidual history:\n"
        << summary.history_text();
    throw ConvergenceError(msg.str(), summary);
  };

  equations.residual(x.data(), f.data());
  IterationRecord current = norms(f);
  double current_merit = merit(f);
  Eigen::VectorXd trial(n), plain(n);
  AndersonMixing anderson(kAndersonDepth);
  for (int it = 0;; ++it) {
    if (options.turbulence == Turbulence::MixingLength && it > 0) {
      eddy.update(x.data(), nu_cell);
      equations.set_viscosity(nu_cell);
      anderson.reset();  // the equations changed: the history no longer applies
      equations.residual(x.data(), f.data());
      current = norms(f);
      current_merit = merit(f);
    }
    current.cfl = cfl;
    summary.history.push_back(current);
    summary.iterations = it;
    if (options.verbose)
      std::fprintf(stderr, "flow: iter %3d  momentum %.3e  continuity %.3e  cfl %.1e\n", it,
                   current.momentum, current.continuity, cfl);
    if (options.on_iteration) options.on_iteration(it, current.momentum, current.continuity);
    if (!std::isfinite(current_merit)) fail("the residual became NaN");
    if (current.momentum < options.tolerance && current.continuity < options.tolerance &&
        (options.turbulence == Turbulence::None || eddy.settled())) {
      summary.converged = true;
      break;
    }
    if (it >= max_iterations) fail("no convergence");

    // Refactorize unless the last step showed the current factorization
    // still converging fast enough (kChordRatio).
    if (refactor) {
      equations.update_jacobian(x.data());
      if (cfl < 1e15) equations.add_to_momentum_diagonal(scales.speed / (cfl * h));
      if (!nullspace && !pairing) {
        if (options.nullspace) nullspace.emplace(grid, equations.jacobian());
        if (nullspace && !nullspace->applicable()) nullspace.reset();
        if (!nullspace) {
          pairing.emplace(grid, equations.jacobian());
          lu.analyze(pairing->permuted(equations.jacobian()));
        }
        summary.linear_solver = nullspace ? "nullspace" : "coupled";
      }
      const auto t_factor = std::chrono::steady_clock::now();
      const bool factored = nullspace ? nullspace->factorize(equations.jacobian())
                                      : lu.factorize(pairing->permuted(equations.jacobian()));
      summary.factor_seconds +=
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t_factor).count();
      ++summary.factorizations;
      if (!factored) {
        cfl /= 10.0;
        if (cfl < 1e-3) fail("the Newton matrix is singular");
        continue;
      }
    }
    const bool fresh = refactor;
    const auto t_solve = std::chrono::steady_clock::now();
    if (nullspace) {
      rhs = -f;
      nullspace->solve(equations.jacobian(), rhs.data(), step.data());
    } else {
      pairing->permute(f.data(), rhs.data());
      rhs = -rhs;
      lu.solve(pairing->permuted_matrix(), rhs.data(), step.data());
    }
    summary.solve_seconds +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t_solve).count();
    // Mix the chord step with the previous ones of this factorization.
    if (fresh) anderson.reset();
    plain = step;
    bool mixed = anderson.mix(x, step);
    double lambda = 1.0, trial_merit = HUGE_VAL;
    for (;;) {
      for (lambda = 1.0; lambda >= 1.0 / 16; lambda *= 0.5) {
        trial = x + lambda * step;
        equations.residual(trial.data(), f_trial.data());
        trial_merit = merit(f_trial);
        if (std::isfinite(trial_merit) && trial_merit < (1.0 - 1e-4 * lambda) * current_merit)
          break;
        // The first step goes from rest to a flow that satisfies continuity (a
        // Stokes-like solve); it is taken whole even if momentum grows.
        if (it == 0 && !coarse && std::isfinite(trial_merit)) break;
      }
      if (lambda >= 1.0 / 16 || !mixed) break;
      // The mixed step failed: forget the history and try the plain one.
      anderson.reset();
      step = plain;
      mixed = false;
    }
    if (lambda < 1.0 / 16) {
      // No cut-back helped. Renew a stale factorization first; with a fresh
      // one, take a shorter pseudo-time step from the same point.
      if (fresh) cfl = std::min(cfl, 1e3) / 10.0;
      if (cfl < 1e-3) fail("the pseudo-time step collapsed");
      refactor = true;
      anderson.reset();
      continue;
    }
    const double ratio = trial_merit / current_merit;
    refactor = ratio > (options.turbulence == Turbulence::None ? kChordRatio : kChordRatioLagged);
    if (fresh && lambda == 1.0) cfl = std::min(cfl / std::max(ratio, 0.1), 1e15);
    x.swap(trial);
    f.swap(f_trial);
    current = norms(f);
    current_merit = trial_merit;
  }

  // Unpack the unknowns into full face arrays.
  std::vector<double> face[2];
  for (int c = 0; c < 2; ++c) {
    face[c].resize(grid.face_count(c));
    for (std::size_t k = 0; k < face[c].size(); ++k) {
      const int col = grid.column(c, k);
      face[c][k] = col >= 0 ? x[col] : grid.fixed_value(c, k);
    }
  }
  std::vector<double> pressure(shape.size(), 0.0);
  for (std::size_t k = 0; k < shape.size(); ++k)
    if (const int col = grid.pressure_column(k); col >= 0) pressure[k] = x[col];

  // Mass balance through the openings (per metre of depth).
  for (int c = 0; c < 2; ++c) {
    for (int b = 0; b < grid.n_across(c); ++b) {
      for (int a : {0, grid.n_along(c)}) {
        const std::size_t k = grid.face(c, a, b);
        const double inward = (a == 0 ? 1.0 : -1.0) * face[c][k] * grid.h_across(c);
        if (grid.kind(c, k) == kOutflow)
          summary.outflow -= inward;
        else if (inward > 0.0)
          summary.inflow += inward;
      }
    }
  }
  summary.mass_imbalance =
      summary.inflow > 0.0 ? std::abs(summary.inflow - summary.outflow) / summary.inflow : 0.0;
  summary.momentum_residual = current.momentum;
  summary.continuity_residual = current.continuity;
  summary.max_eddy_viscosity = eddy.max_eddy_viscosity();

  FlowResult result{WindField(shape, std::move(face[0]), std::move(face[1]), std::move(pressure),
                              grid.solid_cells()),
                    std::move(summary)};
  result.summary.max_speed = result.wind.max_speed();
  result.summary.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace plumekit::cfd
