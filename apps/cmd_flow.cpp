// plumekit flow: the steady wind field of a map.
#include <cmath>
#include <iostream>
#include <sstream>

#include "apps/cli.hpp"
#include "apps/commands.hpp"
#include "cfd/flow_output.hpp"
#include "cfd/flow_policy.hpp"
#include "cfd/openfoam_report.hpp"
#include "core/output_target.hpp"
#include "core/progress.hpp"
#include "map/map_json.hpp"

namespace plumekit::cli {

namespace {

struct FlowArgs {
  std::string map;
  std::string out;
  cfd::FlowOptions options;
  cfd::OpenFoamOptions foam;
  // Enum fields as their names, read by the library's parsers (cfd/options.hpp).
  std::string turbulence = cfd::to_string(options.turbulence);
  std::string convection = cfd::to_string(options.convection);
  std::string linear_solver = cfd::to_string(options.linear_solver);
  std::string engine = cfd::to_string(foam.engine);
  std::string foam_turbulence = cfd::to_string(foam.turbulence);
};

void bind_engine_options(CLI::App* cmd, FlowArgs& a) {
  cfd::OpenFoamOptions& f = a.foam;
  bind_field(cmd,
             cmd->add_option("--engine", a.engine,
                             "Flow solver: " + cfd::engine_names() +
                                 " (openfoam: OpenFOAM's simpleFoam on the same grid, read back "
                                 "into the same files)"),
             "flow.engine")
      ->capture_default_str();
  bind_field(cmd,
             cmd->add_option("--ranks", f.ranks,
                             "OpenFOAM engine: MPI ranks (1: serial; N: decomposePar, mpirun -np "
                             "N simpleFoam -parallel, reconstructPar)"),
             "flow.ranks")
      ->capture_default_str();
  bind_field(cmd,
             cmd->add_option("--foam-turbulence", a.foam_turbulence,
                             "OpenFOAM engine: turbulence model, " + cfd::foam_turbulence_names() +
                                 " (RANS with wall functions; --nu is then the molecular "
                                 "viscosity)"),
             "flow.openfoam_turbulence")
      ->capture_default_str();
  bind_field(cmd,
             cmd->add_option("--foam-tol", f.tolerance,
                             "OpenFOAM engine: stop when every initial residual is below this"),
             "flow.openfoam_tolerance")
      ->capture_default_str();
  bind_field(cmd,
             cmd->add_option("--foam-max-iter", f.max_iterations,
                             "OpenFOAM engine: fail after this many SIMPLE iterations"),
             "flow.openfoam_max_iterations")
      ->capture_default_str();
  bind_field(cmd,
             cmd->add_option("--keep-case", f.keep_case,
                             "OpenFOAM engine: write the case into this new or empty folder and "
                             "keep it (default: a temporary, removed)"),
             "flow.openfoam_case");
}

void bind_flow_options(CLI::App* cmd, FlowArgs& a) {
  cfd::FlowOptions& o = a.options;
  bind_field(cmd, cmd->add_option("--cell", o.cell, cfd::kCellHelp), "flow.cell")
      ->capture_default_str();
  bind_field(cmd,
             cmd->add_flag("--strict-gaps", o.strict_gaps,
                           "Refuse a map with gaps open in it but narrower than a cell, instead "
                           "of closing them with a warning"),
             "flow.strict_gaps");
  bind_field(cmd, cmd->add_option("--nu", o.nu, "Kinematic (effective) viscosity, m^2/s"),
             "flow.nu")
      ->capture_default_str();
  bind_field(cmd,
             cmd->add_option("--turbulence", a.turbulence,
                             "Turbulence closure: " + cfd::turbulence_names()),
             "flow.turbulence")
      ->capture_default_str();
  bind_field(cmd,
             cmd->add_option("--convection", a.convection,
                             "Convection scheme: " + cfd::convection_names() +
                                 " (vanleer: bounded, 2nd order; central: 2nd order; upwind: "
                                 "1st order)"),
             "flow.convection")
      ->capture_default_str();
  bind_field(cmd,
             cmd->add_option("--upwind-fallback", o.upwind_fallback,
                             "When central or vanleer convection does not converge, solve again "
                             "with upwind (the report says so); false: fail instead"),
             "flow.upwind_fallback")
      ->default_str(o.upwind_fallback ? "true" : "false");
  bind_field(
      cmd,
      cmd->add_option("--tol", o.tolerance, "Stop when both normalised residuals are below this"),
      "flow.tolerance")
      ->capture_default_str();
  bind_field(cmd,
             cmd->add_option("--max-iter", o.max_iterations,
                             "Give up after this many Newton iterations (0: 100, or 300 with "
                             "mixing-length)"),
             "flow.max_iterations")
      ->capture_default_str();
  bind_field(cmd,
             cmd->add_option("--linear-solver", a.linear_solver,
                             "Newton systems: " + cfd::linear_solver_names() +
                                 " (nullspace: divergence-free subspace, one unknown per grid "
                                 "node; coupled: u, v, p; same steps, coupled is slower)"),
             "flow.linear_solver")
      ->capture_default_str();
  bind_field(
      cmd,
      cmd->add_flag("--verbose", o.verbose, "Print the residuals of every iteration on stderr"),
      "flow.verbose");
}

// Newton's progress: the fraction of the way from the first residual to the
// tolerance, in log.
void show_progress(cfd::FlowOptions& o, ProgressBar& bar, double& first) {
  o.on_iteration = [&o, &bar, &first](int it, double mom, double cont) {
    const double r = std::max(mom, cont);
    if (it == 0) first = r;
    const double done = std::log(first / r) / std::log(first / o.tolerance);
    std::ostringstream note;
    note.precision(2);
    note << "iteration " << it << ", residual " << std::scientific << r;
    bar.update(std::isfinite(done) ? done : 0.0, note.str());
  };
}

const char* const kWrote = "/{u,v,p,face_u,face_v,solid}.npy, wind.json, wind.vti, wind.png: ";

// Obstacles the grid lets air through are warned of on stderr, whatever the
// output mode (wind.json and the --json report list them as "thin_walls").
void warn_thin_walls(const cfd::FlowSummary& s) {
  if (!s.thin_walls.walls.empty())
    std::cerr << "plumekit: warning: " << cfd::thin_walls_text(s.thin_walls, s.cell) << '\n';
}

void run_openfoam(const FlowArgs& a, const Map& map, OutputDirectory& out) {
  const cfd::OpenFoamResult r = cfd::solve_openfoam(map, a.options, a.foam, out.open());
  warn_thin_walls(r.flow.summary);
  cfd::write_flow(out.open(), map, r.flow.wind, cfd::openfoam_summary_json(r, a.options));
  out.commit();
  nlohmann::ordered_json j{{"ok", true}, {"map", a.map}, {"out", a.out}};
  j.update(cfd::openfoam_report_json(r, a.options));
  report(j, "wrote " + a.out + kWrote + cfd::openfoam_report_text(r));
}

}  // namespace

void add_flow_commands(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "flow",
      "Solve the steady incompressible flow of a map; write u/v/p .npy, wind.json, .vti, .png");
  auto a = std::make_shared<FlowArgs>();
  add_map_argument(cmd, a->map);
  cmd->add_option("--out,-o", a->out, "Output folder: new, empty, or an earlier `flow` output")
      ->required();
  bind_flow_options(cmd, *a);
  bind_engine_options(cmd, *a);
  add_common_flags(cmd);
  cmd->callback([a] {
    cfd::FlowOptions& o = a->options;
    o.turbulence = cfd::parse_turbulence(a->turbulence);
    o.convection = cfd::parse_convection(a->convection);
    o.linear_solver = cfd::parse_linear_solver(a->linear_solver);
    a->foam.engine = cfd::parse_engine(a->engine);
    a->foam.turbulence = cfd::parse_foam_turbulence(a->foam_turbulence);
    a->foam.validate();
    const Map map = read_map(a->map);
    OutputDirectory out(a->out, "flow", {a->map});
    if (a->foam.engine == cfd::Engine::OpenFoam) return run_openfoam(*a, map, out);
    ProgressBar bar("flow");
    double first = 0.0;
    show_progress(o, bar, first);
    const cfd::WindResult wind = cfd::solve_wind(map, o);
    bar.finish();
    warn_thin_walls(wind.flow.summary);
    cfd::write_flow(out.open(), map, wind.flow, o);
    out.commit();
    nlohmann::ordered_json j{{"ok", true}, {"map", a->map}, {"out", a->out}};
    j.update(cfd::flow_report_json(wind, o));
    report(j, "wrote " + a->out + kWrote + cfd::flow_report_text(wind));
  });
}

}  // namespace plumekit::cli
