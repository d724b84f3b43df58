#include "cfd/newton.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include <Eigen/IterativeLinearSolvers>

#include "core/interrupt.hpp"
#include "core/option_check.hpp"

namespace plumekit::cfd {

namespace {

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
// A start interpolated from a coarser grid is projected onto the divergence-free
// fields (project_start) on grids with at least this many unknowns: above every
// 10 x 4 m map's 5 cm grid (44 150), whose flows keep their bytes.
constexpr int kProjectFrom = 50000;
// The projection's conjugate-gradient iterations (Jacobi preconditioner). The
// divergence to remove sits where the fine grid's obstacles differ from the
// coarse grid's, and the first iterations remove it: 40 leave 3 % (depot) to
// 26 % (tb3_world) of it, and Newton then needs no more steps than after the
// exact projection (CHOLMOD), fewer on tb3_world (16 against 21), for a fifth
// of its time (0.08 s against 0.45 s at 5 cm).
constexpr int kProjectIterations = 40;

double since(Newton::Clock::time_point t) {
  return std::chrono::duration<double>(Newton::Clock::now() - t).count();
}

// What to change when Newton does not converge. At a high Reynolds number the
// flow may have no steady state on this grid (a larger viscosity, a finer
// cell or upwinding help); at a low one the viscous terms dwarf the residual's
// scale, so round-off alone keeps it above the tolerance (a smaller viscosity
// or a looser tolerance help).
std::string convergence_advice(double reynolds, const FlowOptions& o) {
  if (reynolds < 1.0)
    return "The flow is dominated by viscosity: try a smaller flow.nu (the default is " +
           default_text(flow_option_table().entry("flow.nu")) +
           " m^2/s) or a larger flow.tolerance (now " + compact(o.tolerance) + ").";
  std::string advice = "Try a larger flow.nu, a finer flow.cell";
  if (o.convection != Convection::Upwind) advice += ", or upwind convection (flow.convection)";
  return advice + ".";
}

}  // namespace

Scales reference_scales(const Map& map, const FlowOptions& o) {
  Scales s;
  s.length = std::min(map.width, map.height);
  double u = o.closed ? 0.0 : map.reference_speed();
  for (double w : o.wall_speed)
    u = std::max(u, std::abs(w));
  s.speed = u > 0.0 ? u : 1.0;
  return s;
}

Newton::Newton(const StaggeredGrid& grid, const FlowOptions& options, const Scales& scales,
               FlowSummary& summary, Clock::time_point start)
    : grid_(grid),
      options_(options),
      scales_(scales),
      summary_(summary),
      start_(start),
      equations_(grid, options.convection),
      eddy_(grid, options),
      anderson_(kAndersonDepth),
      n_(grid.unknowns()),
      n_mom_(grid.velocity_unknowns()),
      max_iterations_(options.max_iterations > 0                       ? options.max_iterations
                      : options.turbulence == Turbulence::MixingLength ? 300
                                                                       : 100),
      h_(std::min(grid.shape().dx(), grid.shape().dy())),
      nu_cell_(grid.shape().size(), options.nu),
      weight_(n_),
      f_(n_),
      f_trial_(n_),
      step_(n_),
      rhs_(n_) {
  equations_.set_viscosity(nu_cell_);
  weight_.head(n_mom_).setConstant(scales.length / (scales.speed * scales.speed));
  weight_.tail(n_ - n_mom_).setConstant(scales.length / scales.speed);
}

IterationRecord Newton::norms(const Eigen::VectorXd& r) const {
  IterationRecord rec;
  rec.momentum =
      r.head(n_mom_).lpNorm<Eigen::Infinity>() * scales_.length / (scales_.speed * scales_.speed);
  rec.continuity = r.tail(n_ - n_mom_).lpNorm<Eigen::Infinity>() * scales_.length / scales_.speed;
  return rec;
}

// Merit for globalisation: the RMS of the residual scaled like the norms.
double Newton::merit(const Eigen::VectorXd& r) const {
  return std::sqrt(r.cwiseProduct(weight_).squaredNorm() / n_);
}

void Newton::evaluate_residual() {
  equations_.residual(x_.data(), f_.data());
  current_ = norms(f_);
  current_merit_ = merit(f_);
}

void Newton::run(Eigen::VectorXd& x, bool from_coarse) {
  x_ = std::move(x);
  evaluate_residual();
  if (from_coarse && n_ >= kProjectFrom) project_start();
  for (int it = 0;; ++it) {
    check_interrupt();  // a caller's Ctrl-C (core/interrupt.hpp)
    if (options_.turbulence == Turbulence::MixingLength && it > 0) lag_viscosity();
    record(it);
    if (!std::isfinite(current_merit_)) fail("the residual became NaN");
    if (converged()) break;
    if (it >= max_iterations_) fail("no convergence");
    // Refactorize unless the last step showed the current factorization
    // still converging fast enough (kChordRatio).
    const bool fresh = refactor_;
    if (refactor_ && !factor()) continue;
    solve_step();
    // The first step goes from rest to a flow that satisfies continuity (a
    // Stokes-like solve); it is taken whole even if momentum grows.
    const double lambda = line_search(fresh, it == 0 && !from_coarse);
    if (lambda > 0.0)
      accept_step(lambda);
    else
      after_failed_step(fresh);
  }
  summary_.converged = true;
  x = std::move(x_);
}

void Newton::project_start() {
  // The interpolated coarse flow violates continuity where the fine grid's
  // obstacles differ from the coarse grid's (a residual as large as the
  // momentum one), and the line search then cuts the first steps short or
  // rejects them: depot at 5 cm lost three fine factorizations, and its 10 cm
  // grid found no central flow at all. The nearest velocity that satisfies
  // continuity is u - D'l with D D' l = D u + c, a cell Laplacian, solved
  // only roughly (kProjectIterations): Newton's first step satisfies
  // continuity exactly anyway.
  if (!grid_.has_outflow()) return;  // a closed box pins one pressure instead
  const Eigen::SparseMatrix<double> d = equations_.continuity_matrix();
  const Eigen::SparseMatrix<double> dd = d * d.transpose();
  Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Lower | Eigen::Upper> cg;
  cg.setMaxIterations(kProjectIterations);
  cg.compute(dd);
  const Eigen::VectorXd lambda = cg.solve(f_.tail(n_ - n_mom_));
  if (!lambda.allFinite()) return;  // keep the start as it is
  x_.head(n_mom_) -= d.transpose() * lambda;
  evaluate_residual();
}

void Newton::lag_viscosity() {
  eddy_.update(x_.data(), nu_cell_);
  equations_.set_viscosity(nu_cell_);
  anderson_.reset();  // the equations changed: the history no longer applies
  evaluate_residual();
}

void Newton::record(int it) {
  current_.cfl = cfl_;
  summary_.history.push_back(current_);
  summary_.iterations = it;
  if (options_.verbose)
    std::fprintf(stderr, "flow: iter %3d  momentum %.3e  continuity %.3e  cfl %.1e\n", it,
                 current_.momentum, current_.continuity, cfl_);
  if (options_.on_iteration) options_.on_iteration(it, current_.momentum, current_.continuity);
}

bool Newton::converged() const {
  return current_.momentum < options_.tolerance && current_.continuity < options_.tolerance &&
         (options_.turbulence == Turbulence::None || eddy_.settled());
}

void Newton::assemble() {
  equations_.update_jacobian(x_.data());
  if (cfl_ < 1e15) equations_.add_to_momentum_diagonal(scales_.speed / (cfl_ * h_));
  if (!linear_solver_) {
    linear_solver_ = make_linear_solver(options_.linear_solver, grid_, equations_.jacobian());
    summary_.linear_solver = linear_solver_->name();
  }
}

bool Newton::factor() {
  assemble();
  const auto t = Clock::now();
  const bool first = summary_.factorizations == 0;
  bool factored = linear_solver_->factorize(equations_.jacobian());
  if (!factored && first) factored = switch_to_coupled();
  summary_.factor_seconds += since(t);
  ++summary_.factorizations;
  if (factored) return true;
  cfl_ /= 10.0;
  if (cfl_ < 1e-3) fail("the Newton matrix is singular");
  return false;
}

bool Newton::switch_to_coupled() {
  // A reduced matrix K that is singular at the grid's first Newton matrix, whose
  // coupled matrix is not, means the nullspace basis is short for this
  // geometry (depot at 5 cm, docs/design/flow-solver.md "Building scale"); the coupled
  // solver gives the same steps there.
  if (std::string(linear_solver_->name()) != "nullspace") return false;
  auto coupled = make_linear_solver(LinearSolverKind::Coupled, grid_, equations_.jacobian());
  if (!coupled->factorize(equations_.jacobian())) return false;
  linear_solver_ = std::move(coupled);
  summary_.linear_solver = linear_solver_->name();
  return true;
}

void Newton::solve_step() {
  const auto t = Clock::now();
  rhs_ = -f_;
  linear_solver_->solve(equations_.jacobian(), rhs_.data(), step_.data());
  summary_.solve_seconds += since(t);
}

double Newton::backtrack(bool take_whole) {
  for (double lambda = 1.0; lambda >= 1.0 / 16; lambda *= 0.5) {
    trial_ = x_ + lambda * step_;
    equations_.residual(trial_.data(), f_trial_.data());
    trial_merit_ = merit(f_trial_);
    if (!std::isfinite(trial_merit_)) continue;
    if (trial_merit_ < (1.0 - 1e-4 * lambda) * current_merit_ || take_whole) return lambda;
  }
  return 0.0;
}

double Newton::line_search(bool fresh, bool take_whole) {
  // Mix the chord step with the previous ones of this factorization.
  if (fresh) anderson_.reset();
  plain_ = step_;
  bool mixed = anderson_.mix(x_, step_);
  for (;;) {
    const double lambda = backtrack(take_whole);
    if (lambda > 0.0 || !mixed) return lambda;
    // The mixed step failed: forget the history and try the plain one.
    anderson_.reset();
    step_ = plain_;
    mixed = false;
  }
}

void Newton::after_failed_step(bool fresh) {
  // No cut-back helped. Renew a stale factorization first; with a fresh one,
  // take a shorter pseudo-time step from the same point.
  if (fresh) cfl_ = std::min(cfl_, 1e3) / 10.0;
  if (cfl_ < 1e-3) fail("the pseudo-time step collapsed");
  refactor_ = true;
  anderson_.reset();
}

void Newton::accept_step(double lambda) {
  // The pseudo-time step grows with the merit's fall (SER) after every full
  // step, chord steps included, and the next factorization uses it. (Growing
  // it only after fresh factorizations kept it near 1 for 60 steps and 47
  // factorizations on depot's 10 cm grid: 13.6 s against 4.4 s.)
  const double ratio = trial_merit_ / current_merit_;
  refactor_ = ratio > (options_.turbulence == Turbulence::None ? kChordRatio : kChordRatioLagged);
  if (lambda == 1.0) cfl_ = std::min(cfl_ / std::max(ratio, 0.1), 1e15);
  x_.swap(trial_);
  f_.swap(f_trial_);
  current_ = norms(f_);
  current_merit_ = trial_merit_;
}

void Newton::fail(const std::string& why) const {
  summary_.seconds = since(start_);
  const double reynolds = scales_.speed * scales_.length / options_.nu;
  std::ostringstream msg;
  msg << "flow solver: " << why << " after " << summary_.iterations << " iterations on a "
      << grid_.nx() << " x " << grid_.ny() << " grid (nu " << options_.nu << " m^2/s, "
      << to_string(options_.convection) << " convection, Reynolds number " << compact(reynolds)
      << "). " << convergence_advice(reynolds, options_) << "\nResidual history:\n"
      << summary_.history_text();
  throw ConvergenceError(msg.str(), summary_);
}

}  // namespace plumekit::cfd
