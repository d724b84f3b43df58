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
};

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
  add_table_flags(cmd, a->foam, cfd::openfoam_option_table());
  add_common_flags(cmd);
  cmd->callback([a] {
    cfd::FlowOptions& o = a->options;
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
