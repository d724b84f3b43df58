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
  // The engine's enum fields as their names, read by the library's parsers.
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
  add_table_flags(cmd, a->options, cfd::flow_option_table());
  bind_engine_options(cmd, *a);
  add_common_flags(cmd);
  cmd->callback([a] {
    cfd::FlowOptions& o = a->options;
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
