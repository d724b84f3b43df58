#pragma once
// Options of the steady flow solver, with the defaults the dataset generator
// uses. See docs/design/flow-solver.md for why these defaults give converged steady flows.
#include <array>
#include <functional>
#include <string>

#include "core/option_table.hpp"

namespace plumekit {
struct Map;
}

namespace plumekit::cfd {

enum class Turbulence { None, MixingLength };
enum class Convection {
  Upwind,   // first order, bounded
  Central,  // second order, unbounded when the cell Peclet number exceeds 2
  VanLeer,  // second order where smooth, bounded (TVD, van Leer limiter)
};

// How the Newton systems are solved (linear_solver.hpp); both give the same
// steps to round-off.
enum class LinearSolverKind {
  Nullspace,  // the divergence-free subspace, one unknown per grid node
  Coupled,    // the (u, v, p) matrix with paired rows
};

// The names the options are written and read by ("mixing-length", "vanleer",
// "coupled"), and the list of them for help texts ("upwind, central, vanleer").
const char* to_string(Turbulence t);
const char* to_string(Convection c);
const char* to_string(LinearSolverKind k);
std::string turbulence_names();
std::string convection_names();
std::string linear_solver_names();
// The option a name denotes; OptionError naming the field ("flow.convection")
// and the valid names otherwise.
Turbulence parse_turbulence(const std::string& name);
Convection parse_convection(const std::string& name);
LinearSolverKind parse_linear_solver(const std::string& name);

// The default cell (FlowOptions::cell = 0): 5 cm on every arena whose 5 cm
// grid has at most kAutoCellMaxCells cells (every building-scale map: the
// 10 x 4 m arenas, tb3_world, depot, warehouse); on larger arenas the
// smallest of 1, 1.2, 1.5, 2, 2.5, 3, 4, 5, 6, 8 x 10^k m that gives at most
// that many cells. It depends on the arena's size only, never on the machine.
inline constexpr double kDefaultCell = 0.05;
inline constexpr double kAutoCellMaxCells = 640000;
struct FlowOptions {
  // m; cells per side = round(extent / cell). 0 (the default) chooses from the
  // arena's size: resolved_cell() below.
  double cell = 0.0;
  double nu = 0.01;  // m^2/s, (effective) kinematic viscosity
  Turbulence turbulence = Turbulence::None;
  Convection convection = Convection::Central;
  // Mixing-length closure: nu_t = lm^2 |S|, lm = min(kappa d, lm_max), d the
  // distance to the nearest no-slip surface. lm_max <= 0 means 0.09 times half
  // the arena's smaller side (Escudier's 0.09 delta).
  double kappa = 0.41;
  double lm_max = 0.0;
  // Stop when both normalised residuals (see FlowSummary) are below this.
  double tolerance = 1e-8;
  // Give up after this many iterations; 0 means 100, or 300 with the
  // mixing-length closure, whose lagged eddy viscosity settles slowly at low
  // viscosity (130-240 iterations on some cluttered maps at nu = 0.001).
  int max_iterations = 0;
  // Tangential velocity of each wall (left, right, bottom, top), m/s, in the
  // direction of increasing x or y along it: a moving lid. 0 is no-slip.
  std::array<double, 4> wall_speed{0.0, 0.0, 0.0, 0.0};
  // Treat the inlet and outlet as walls: a closed box, as in the lid-driven
  // cavity. The pressure is then fixed to 0 in one cell.
  bool closed = false;
  // Grid sequencing: first solve on a grid twice as coarse (recursively, down
  // to about 50 cells across) and start Newton from that flow. Newton then
  // needs fewer of the expensive fine-grid factorizations.
  bool sequencing = true;
  // Solve the Newton systems in the divergence-free subspace (one unknown per
  // grid node, nullspace_solver.hpp), or on the coupled (u, v, p) matrix with
  // paired rows (coupled_solver.hpp). Both give the same steps to round-off;
  // the coupled one is also the fallback where the nullspace checks fail.
  LinearSolverKind linear_solver = LinearSolverKind::Nullspace;
  // The flow policy (cfd::solve_wind, flow_policy.hpp): when Newton does not
  // converge with central or van Leer convection, solve again with first-order
  // upwind, and report it. cfd::solve itself ignores this.
  bool upwind_fallback = true;
  // A gap between two obstacles (or an obstacle and a wall) that is open in
  // the map but narrower than a cell is closed on the grid, with a warning
  // (cfd/gap_closing.hpp). true refuses such a grid instead (OptionError on
  // flow.cell naming the narrowest gap and a cell that keeps it open).
  bool strict_gaps = false;
  bool verbose = false;  // a line per iteration on stderr
  // Called after each iteration with (iteration, momentum, continuity residual).
  std::function<void(int, double, double)> on_iteration;

  // Throws OptionError naming the field ("flow.cell", "flow.nu", ...) and its
  // allowed range (flow_option_table(); docs/options.md). cfd::solve calls it.
  void validate() const;
};

// Every option of FlowOptions but wall_speed and on_iteration: names, flags,
// ranges and help (core/option_table.hpp). The commands that take --cell bind
// its "flow.cell" entry.
const OptionTable<FlowOptions>& flow_option_table();

// The cell a grid is made with: options.cell, or the default rule above when
// it is 0. Every grid of a flow solve is made from this.
double resolved_cell(double width, double height, const FlowOptions& options);
double resolved_cell(const Map& map, const FlowOptions& options);

}  // namespace plumekit::cfd
