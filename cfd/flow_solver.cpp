#include "cfd/flow_solver.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>
#include <sstream>

#include "cfd/grid_check.hpp"
#include "cfd/newton.hpp"
#include "cfd/staggered_grid.hpp"
#include "core/option_check.hpp"

namespace plumekit::cfd {

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
// Coarse grids only provide a start; their own discretisation error is far
// above this.
constexpr double kCoarseTolerance = 1e-4;
// A coarse grid whose cell Peclet number U h / nu is above this is solved with
// upwind convection: central's flow there is no better a start, and Newton
// needs far more steps for it (tb3_world's 40 cm grid: 39 to 52 iterations
// and 18 factorizations). The shipped maps' 10 cm grids (10) stay central.
constexpr double kCoarseUpwindPeclet = 15.0;

// The coarse flow to start from, if a twice-coarser grid is worth solving and
// can represent the map; otherwise none (Newton starts from rest).
std::optional<WindField> coarse_start(const Map& map, const FlowOptions& options,
                                      const GridShape& shape) {
  if (!options.sequencing || std::min(shape.nx, shape.ny) < kMinSequencedCells) return std::nullopt;
  FlowOptions coarse = options;
  coarse.cell = 2.0 * std::max(shape.dx(), shape.dy());
  // A start needs no more accuracy than the coarse grid's own discretisation error.
  coarse.tolerance = std::max(options.tolerance, kCoarseTolerance);
  // A coarse grid closes its own narrow gaps (it is only a start), even when
  // the fine grid must refuse them.
  coarse.strict_gaps = false;
  // The coarsest grid starts from rest, where first-order upwinding makes
  // Newton converge in a few steps; its flow is only a start for the next grid.
  const GridShape cs = GridShape::with_cell(map.width, map.height, coarse.cell);
  if (std::min(cs.nx, cs.ny) < kMinSequencedCells) coarse.convection = Convection::Upwind;
  const double peclet =
      reference_scales(map, options).speed * std::max(cs.dx(), cs.dy()) / options.nu;
  if (peclet > kCoarseUpwindPeclet) coarse.convection = Convection::Upwind;
  coarse.on_iteration = nullptr;
  try {
    return solve(map, coarse).wind;
  } catch (const ConvergenceError&) {
    if (coarse.convection == Convection::Upwind) return std::nullopt;
  } catch (const InputError&) {
    return std::nullopt;  // the coarse grid closes a gap, or seals the openings
  }
  // No steady flow with this scheme on the coarse grid, whose cell Peclet
  // number is twice the fine grid's: an upwind flow is still a far better
  // start than rest (depot at 5 cm, docs/design/flow-solver.md "Building scale").
  coarse.convection = Convection::Upwind;
  try {
    return solve(map, coarse).wind;
  } catch (const InputError&) {
    return std::nullopt;
  }
}

// The summary's description of the grid and the options.
FlowSummary initial_summary(const GridShape& shape, const FlowOptions& options, double cell) {
  FlowSummary summary;
  summary.cell = cell;
  summary.nx = shape.nx;
  summary.ny = shape.ny;
  summary.dx = shape.dx();
  summary.dy = shape.dy();
  summary.nu = options.nu;
  summary.turbulence = options.turbulence;
  summary.convection = options.convection;
  summary.tolerance = options.tolerance;
  return summary;
}

// The face velocities (fixed faces included) and cell pressures of the unknowns.
struct Unpacked {
  std::vector<double> face[2];
  std::vector<double> pressure;
};
Unpacked unpack(const StaggeredGrid& grid, const Eigen::VectorXd& x) {
  Unpacked out;
  for (int c = 0; c < 2; ++c) {
    out.face[c].resize(grid.face_count(c));
    for (std::size_t k = 0; k < out.face[c].size(); ++k) {
      const int col = grid.column(c, k);
      out.face[c][k] = col >= 0 ? x[col] : grid.fixed_value(c, k);
    }
  }
  out.pressure.assign(grid.shape().size(), 0.0);
  for (std::size_t k = 0; k < grid.shape().size(); ++k)
    if (const int col = grid.pressure_column(k); col >= 0) out.pressure[k] = x[col];
  return out;
}

// Mass balance through the openings (per metre of depth).
void mass_balance(const StaggeredGrid& grid, const std::vector<double> (&face)[2],
                  FlowSummary& summary) {
  // Every face on the free space's boundary: the arena's edge and the faces
  // between fluid and solid cells (openings on obstacles' edges).
  for (int c = 0; c < 2; ++c) {
    for (int b = 0; b < grid.n_across(c); ++b) {
      for (int a = 0; a <= grid.n_along(c); ++a) {
        const int side = grid.fluid_side(c, a, b);
        if (side != 1 && side != -1) continue;
        const std::size_t k = grid.face(c, a, b);
        const double inward = side * face[c][k] * grid.h_across(c);
        if (grid.kind(c, k) == kOutflow)
          summary.outflow -= inward;
        else if (inward > 0.0)
          summary.inflow += inward;
      }
    }
  }
  summary.mass_imbalance =
      summary.inflow > 0.0 ? std::abs(summary.inflow - summary.outflow) / summary.inflow : 0.0;
}

double since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace

FlowResult solve(const Map& map, const FlowOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  options.validate();
  check_grid_size(map, options);  // before any grid is made: the size and the memory
  const double cell = resolved_cell(map, options);
  const GridShape shape = GridShape::with_cell(map.width, map.height, cell);
  const std::vector<GapReport> gaps = check_grid(map, shape, options);
  const StaggeredGrid grid(map, shape, options);
  FlowSummary summary = initial_summary(shape, options, cell);
  summary.closed_gaps = summarize_gaps(map, gaps);
  summary.thin_walls = summarize_thin_walls(map, find_thin_walls(map, shape, grid.solid_cells()));

  const auto t_coarse = std::chrono::steady_clock::now();
  const std::optional<WindField> coarse = coarse_start(map, options, shape);
  summary.coarse_seconds = since(t_coarse);
  Eigen::VectorXd x =
      coarse ? interpolate(grid, *coarse) : Eigen::VectorXd::Zero(grid.unknowns()).eval();
  Newton newton(grid, options, reference_scales(map, options), summary, start);
  newton.run(x, coarse.has_value());

  Unpacked fields = unpack(grid, x);
  mass_balance(grid, fields.face, summary);
  summary.momentum_residual = newton.residuals().momentum;
  summary.continuity_residual = newton.residuals().continuity;
  summary.max_eddy_viscosity = newton.eddy_viscosity().max_eddy_viscosity();

  FlowResult result{WindField(shape, std::move(fields.face[0]), std::move(fields.face[1]),
                              std::move(fields.pressure), grid.solid_cells()),
                    std::move(summary)};
  result.summary.max_speed = result.wind.max_speed();
  result.summary.seconds = since(start);
  return result;
}

}  // namespace plumekit::cfd
