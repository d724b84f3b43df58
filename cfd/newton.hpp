#pragma once
// Newton's method on one grid's flow equations (cfd::solve's inner loop), as
// named steps: assemble the Newton matrix, factor it, solve for the step, a
// backtracking line search (with Anderson-mixed chord steps), pseudo-transient
// continuation, and the convergence test. docs/design/flow-solver.md, "Numerics", says why
// each step is as it is.
#include <Eigen/Core>
#include <chrono>
#include <memory>
#include <string>
#include <vector>

#include "cfd/anderson.hpp"
#include "cfd/eddy_viscosity.hpp"
#include "cfd/flow_solver.hpp"
#include "cfd/linear_solver.hpp"
#include "cfd/navier_stokes.hpp"

namespace plumekit::cfd {

// Reference scales of the normalised residuals (FlowSummary).
struct Scales {
  double speed = 1.0;   // the inlet speed or the fastest wall, m/s
  double length = 1.0;  // the arena's smaller side, m
};
Scales reference_scales(const Map& map, const FlowOptions& options);

class Newton {
 public:
  using Clock = std::chrono::steady_clock;
  // `summary` is filled as the iteration goes (history, counts, timings);
  // `start` is when the whole solve began, for the time a failure reports.
  Newton(const StaggeredGrid& grid, const FlowOptions& options, const Scales& scales,
         FlowSummary& summary, Clock::time_point start);

  // Iterates from `x` (a coarse grid's flow, or rest) until converged; x is
  // then the solution. Throws ConvergenceError.
  void run(Eigen::VectorXd& x, bool from_coarse);
  // The normalised residuals at the solution.
  const IterationRecord& residuals() const { return current_; }
  const EddyViscosity& eddy_viscosity() const { return eddy_; }

 private:
  IterationRecord norms(const Eigen::VectorXd& r) const;
  double merit(const Eigen::VectorXd& r) const;
  void evaluate_residual();
  // A coarse grid's interpolated flow made to satisfy continuity (kProjectFrom).
  void project_start();
  // Mixing length: the lagged eddy viscosity, recomputed from the latest flow.
  void lag_viscosity();
  void record(int it);
  bool converged() const;
  // J + I/dtau at x; the linear solver is made with the first one.
  void assemble();
  // Assembles and factors; false (after shortening the pseudo-time step) when
  // the matrix is singular.
  bool factor();
  // The coupled solver instead of a nullspace one whose first K is singular;
  // false (keeping the solver) when the coupled matrix is singular too.
  bool switch_to_coupled();
  void solve_step();
  // Backtracks along `step_` from x; the step length taken, or 0 when no
  // cut-back lowers the merit. `take_whole`: the first step from rest.
  double backtrack(bool take_whole);
  // The Anderson-mixed step first, the plain one if that fails.
  double line_search(bool fresh, bool take_whole);
  // Pseudo-transient continuation after a failed or an accepted step.
  void after_failed_step(bool fresh);
  void accept_step(double lambda);
  [[noreturn]] void fail(const std::string& why) const;

  const StaggeredGrid& grid_;
  const FlowOptions& options_;
  const Scales scales_;
  FlowSummary& summary_;
  const Clock::time_point start_;
  NavierStokes equations_;
  EddyViscosity eddy_;
  std::unique_ptr<LinearSolver> linear_solver_;
  AndersonMixing anderson_;
  int n_, n_mom_;
  int max_iterations_;
  double h_;  // the smaller cell side, for the pseudo-time step
  // Each step solves (J + I/dtau) dx = -F, dtau = cfl h / U: a huge cfl is
  // Newton, a small one a damped implicit time step.
  double cfl_ = 1e6;
  bool refactor_ = true;
  std::vector<double> nu_cell_;
  Eigen::VectorXd weight_;  // merit weights, the norms' scales per row
  Eigen::VectorXd x_, f_, trial_, f_trial_, step_, plain_, rhs_;
  IterationRecord current_;
  double current_merit_ = 0.0, trial_merit_ = 0.0;
};

}  // namespace plumekit::cfd
