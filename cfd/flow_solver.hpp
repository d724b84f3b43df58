#pragma once
// cfd::solve: the steady wind field of a map.
//
//   FlowResult r = cfd::solve(map, options);
//   Vec2 wind = r.wind.at({2.0, 1.5});
//
// Newton's method on the coupled discrete equations (navier_stokes.hpp), with
// pseudo-transient continuation for robustness far from the solution, and
// every linear solve through UMFPACK (the sparsity pattern is analysed once
// and reused by every factorization).
#include <string>
#include <vector>

#include "cfd/gap_closing.hpp"
#include "cfd/options.hpp"
#include "cfd/thin_walls.hpp"
#include "cfd/wind_field.hpp"
#include "core/error.hpp"
#include "map/map.hpp"

namespace plumekit::cfd {

struct IterationRecord {
  double momentum = 0.0;    // normalised momentum residual
  double continuity = 0.0;  // normalised continuity residual
  double cfl = 0.0;         // pseudo-time step as a CFL number (huge = pure Newton)
};

// What happened. Residuals are max-norms, normalised by the reference speed U
// (inlet or lid) and length L (the arena's smaller side): momentum by U^2/L,
// continuity by U/L.
struct FlowSummary {
  int nx = 0, ny = 0;
  double dx = 0.0, dy = 0.0;
  double cell = 0.0;  // m, the cell asked for (resolved_cell: the default resolved)
  // The gaps open in the map but narrower than a cell, which the grid closed
  // (gap_closing.hpp); positions in the map frame.
  ClosedGaps closed_gaps;
  // The obstacles the grid lets air through (thin_walls.hpp), positions in
  // the map frame.
  ThinWalls thin_walls;
  double nu = 0.0;
  Turbulence turbulence = Turbulence::None;
  Convection convection = Convection::Central;
  double tolerance = 0.0;
  bool converged = false;
  int iterations = 0;
  int factorizations = 0;
  // "nullspace" or "coupled": the linear solver used on this grid (coupled
  // when asked for, or where the nullspace solver does not apply).
  std::string linear_solver;
  std::vector<IterationRecord> history;
  double momentum_residual = 0.0;
  double continuity_residual = 0.0;
  double inflow = 0.0;          // m^2/s per metre of depth, through the inlet
  double outflow = 0.0;         // through the outlet
  double mass_imbalance = 0.0;  // |inflow - outflow| / inflow
  double max_speed = 0.0;
  double max_eddy_viscosity = 0.0;
  double seconds = 0.0;              // wall time of the whole solve
  double coarse_seconds = 0.0;       // of which: the coarser grids (sequencing)
  double factor_seconds = 0.0;       //   LU factorizations on this grid
  double solve_seconds = 0.0;        //   triangular solves on this grid
  std::string history_text() const;  // a table of the residual history
};

struct FlowResult {
  WindField wind;
  FlowSummary summary;
};

// The solver stopped without converging, or met a NaN. Bad input (exit 2):
// the message says what to change, and the history is attached.
class ConvergenceError : public InputError {
 public:
  ConvergenceError(const std::string& message, FlowSummary summary)
      : InputError(message), summary_(std::move(summary)) {}
  const FlowSummary& summary() const { return summary_; }

 private:
  FlowSummary summary_;
};

// Throws InputError for options or maps it cannot solve (a non-positive
// viscosity, an inlet that cannot reach the outlet, a gap the grid closes),
// ConvergenceError when Newton does not converge.
FlowResult solve(const Map& map, const FlowOptions& options);

}  // namespace plumekit::cfd
