#include "cfd/openfoam_engine.hpp"

#include <chrono>
#include <fstream>
#include <sstream>

#include "cfd/grid_check.hpp"
#include "cfd/openfoam_case.hpp"
#include "cfd/openfoam_fields.hpp"
#include "cfd/openfoam_run.hpp"
#include "cfd/staggered_grid.hpp"
#include "core/option_check.hpp"

namespace plumekit::cfd {

namespace fs = std::filesystem;

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// The programs a run needs, checked before anything is written.
void require_programs(int ranks) {
  std::vector<std::string> needed{"simpleFoam"};
  if (ranks > 1) needed.insert(needed.end(), {"decomposePar", "reconstructPar", "mpirun"});
  for (const std::string& name : needed)
    if (find_program(name).empty())
      throw InputError(
          "flow.engine openfoam needs OpenFOAM's " + name +
          ", which is not on PATH: install Debian's `openfoam` package" +
          (ranks > 1 ? " and an MPI runtime (`openmpi-bin`)" : std::string()) +
          ", e.g. `sudo apt-get install openfoam openmpi-bin` or scripts/install-deps.sh");
}

// The options the built-in engine has and this one does not.
void check_flow_options(const FlowOptions& flow) {
  flow.validate();
  if (flow.turbulence != Turbulence::None)
    throw OptionError("flow.turbulence",
                      "the mixing-length closure is the built-in engine's; with flow.engine "
                      "openfoam use flow.openfoam_turbulence (laminar or kOmegaSST)");
  if (flow.closed) throw OptionError("flow.closed", "the OpenFOAM engine needs an outlet");
  for (double w : flow.wall_speed)
    if (w != 0.0) throw OptionError("flow.wall_speed", "the OpenFOAM engine has no moving walls");
}

// The case folder: the one to keep, made new, or a temporary in work_dir.
fs::path case_folder(const OpenFoamOptions& foam, const fs::path& work_dir) {
  if (foam.keep_case.empty()) {
    const fs::path dir = work_dir / "openfoam-case";
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
  }
  const fs::path dir = fs::absolute(foam.keep_case);
  std::error_code ec;
  if (fs::exists(dir) && !(fs::is_directory(dir) && fs::is_empty(dir)))
    throw OptionError("flow.openfoam_case", dir.string() + " exists and is not an empty folder");
  fs::create_directories(dir, ec);
  if (ec) throw OptionError("flow.openfoam_case", dir.string() + ": " + ec.message());
  return dir;
}

// Removes the temporary case however the solve ends.
struct CaseGuard {
  fs::path dir;
  bool keep;
  ~CaseGuard() {
    std::error_code ec;
    if (!keep) fs::remove_all(dir, ec);
  }
};

// decomposePar + mpirun simpleFoam -parallel + reconstructPar, or simpleFoam.
double run_simple_foam(const fs::path& dir, int ranks) {
  if (ranks == 1) return run_foam_program({"simpleFoam"}, dir, "simpleFoam");
  double seconds = run_foam_program({"decomposePar"}, dir, "decomposePar");
  seconds += run_foam_program(
      {"mpirun", "-np", std::to_string(ranks), "--oversubscribe", "simpleFoam", "-parallel"}, dir,
      "simpleFoam");
  return seconds + run_foam_program({"reconstructPar", "-latestTime"}, dir, "reconstructPar");
}

std::string read_text(const fs::path& file) {
  std::ifstream in(file);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string residual_text(const std::map<std::string, double>& residuals) {
  std::ostringstream s;
  s.precision(3);
  for (const auto& [name, value] : residuals)
    s << (s.tellp() > 0 ? ", " : "") << name << " " << value;
  return s.str();
}

// The log's verdict: ConvergenceError unless simpleFoam converged.
void check_converged(const SimpleFoamLog& log, const OpenFoamOptions& foam, FlowSummary summary,
                     const fs::path& dir) {
  summary.iterations = log.iterations;
  if (log.diverged)
    throw ConvergenceError("simpleFoam diverged after " + std::to_string(log.iterations) +
                               " iterations (residuals " + residual_text(log.residuals) +
                               "): try a larger flow.nu or a smaller flow.cell",
                           summary);
  if (!log.converged)
    throw ConvergenceError(
        "simpleFoam did not converge within " + std::to_string(foam.max_iterations) +
            " iterations (flow.openfoam_max_iterations; last residuals " +
            residual_text(log.residuals) + ", flow.openfoam_tolerance " + compact(foam.tolerance) +
            "); the end of its log:\n" + file_tail(dir / "log.simpleFoam", 6),
        summary);
}

}  // namespace

OpenFoamResult solve_openfoam(const Map& map, const FlowOptions& flow, const OpenFoamOptions& foam,
                              const fs::path& work_dir) {
  const auto t0 = std::chrono::steady_clock::now();
  check_flow_options(flow);
  foam.validate();
  require_programs(foam.ranks);
  const double cell = resolved_cell(map, flow);  // flow.cell, or the default from the size
  const GridShape shape = GridShape::with_cell(map.width, map.height, cell);
  const std::vector<GapReport> gaps = check_grid(map, shape, flow);  // closed, as cfd::solve
  const StaggeredGrid grid(map, shape, flow);

  OpenFoamResult r;
  r.run.ranks = foam.ranks;
  r.run.turbulence = foam.turbulence;
  const CaseGuard guard{case_folder(foam, work_dir), !foam.keep_case.empty()};
  const FoamMesh mesh = build_foam_mesh(grid);
  write_foam_case(guard.dir, mesh, grid, flow, foam);
  r.run.case_seconds = seconds_since(t0);

  r.run.solver_seconds = run_simple_foam(guard.dir, foam.ranks);
  const SimpleFoamLog log = parse_simplefoam_log(read_text(guard.dir / "log.simpleFoam"));
  FlowSummary partial;
  partial.nx = shape.nx, partial.ny = shape.ny, partial.nu = flow.nu;
  check_converged(log, foam, partial, guard.dir);

  const auto t1 = std::chrono::steady_clock::now();
  const std::string time = latest_time(guard.dir);
  if (time.empty()) throw InputError("simpleFoam wrote no result in " + guard.dir.string());
  r.flow = wind_from_foam(grid, mesh, read_foam_field(guard.dir / time / "phi", 1),
                          read_foam_field(guard.dir / time / "p", 1), flow.nu);
  r.run.read_seconds = seconds_since(t1);
  r.run.ranks = log.processes;  // as simpleFoam reports it
  r.run.iterations = log.iterations;
  r.run.converged = log.converged;
  r.run.residuals = log.residuals;
  if (guard.keep) r.run.kept_case = guard.dir.string();

  FlowSummary& s = r.flow.summary;
  s.cell = cell;
  s.closed_gaps = summarize_gaps(map, gaps);
  s.thin_walls = summarize_thin_walls(map, find_thin_walls(map, shape, grid.solid_cells()));
  s.tolerance = foam.tolerance;
  s.converged = true;
  s.iterations = log.iterations;
  s.linear_solver = "simpleFoam";
  s.momentum_residual = std::max(log.residuals.count("Ux") ? log.residuals.at("Ux") : 0.0,
                                 log.residuals.count("Uy") ? log.residuals.at("Uy") : 0.0);
  s.continuity_residual = log.residuals.count("p") ? log.residuals.at("p") : 0.0;
  s.seconds = seconds_since(t0);
  return r;
}

}  // namespace plumekit::cfd
