// plumekit flow: the steady wind field of a map.
#include <malloc.h>

#include <cmath>
#include <sstream>

#include "apps/cli.hpp"
#include "apps/commands.hpp"
#include "cfd/flow_output.hpp"
#include "cfd/flow_solver.hpp"
#include "core/map_json.hpp"
#include "core/output_target.hpp"
#include "core/progress.hpp"

namespace plumekit::cli {

void add_flow_commands(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "flow",
      "Solve the steady incompressible flow of a map; write u/v/p .npy, wind.json, .vti, .png");
  struct Args {
    std::string map = default_map().string();
    std::string out;
    std::string turbulence = "none";
    std::string convection = "central";
    std::string linear_solver = "nullspace";
    cfd::FlowOptions options;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("MAP", a->map, "Map file (JSON)")->capture_default_str();
  cmd->add_option("--out,-o", a->out, "Output folder: new, empty, or an earlier `flow` output")
      ->required();
  bind_field(cmd, cmd->add_option("--cell", a->options.cell, "Cell size in metres"), "flow.cell")
      ->capture_default_str();
  bind_field(cmd, cmd->add_option("--nu", a->options.nu, "Kinematic (effective) viscosity, m^2/s"),
             "flow.nu")
      ->capture_default_str();
  cmd->add_option("--turbulence", a->turbulence, "Turbulence closure")
      ->capture_default_str()
      ->check(CLI::IsMember({"none", "mixing-length"}));
  cmd->add_option(
         "--convection", a->convection,
         "Convection scheme: vanleer (bounded, 2nd order), central (2nd order), upwind (1st)")
      ->capture_default_str()
      ->check(CLI::IsMember({"vanleer", "central", "upwind"}));
  bind_field(cmd,
             cmd->add_option("--tol", a->options.tolerance,
                             "Stop when both normalised residuals are below this"),
             "flow.tolerance")
      ->capture_default_str();
  bind_field(
      cmd,
      cmd->add_option("--max-iter", a->options.max_iterations,
                      "Give up after this many Newton iterations (default 0: 100, or 300 with "
                      "mixing-length)"),
      "flow.max_iterations");
  cmd->add_option("--linear-solver", a->linear_solver,
                  "Newton systems: nullspace (divergence-free subspace, one unknown per grid "
                  "node) or coupled (u, v, p); same steps, coupled is slower")
      ->capture_default_str()
      ->check(CLI::IsMember({"nullspace", "coupled"}));
  cmd->add_flag("--verbose", a->options.verbose,
                "Print the residuals of every iteration on stderr");
  add_common_flags(cmd);
  cmd->callback([a] {
    cfd::FlowOptions& o = a->options;
    o.turbulence = a->turbulence == "none" ? cfd::Turbulence::None : cfd::Turbulence::MixingLength;
    o.convection = a->convection == "vanleer"   ? cfd::Convection::VanLeer
                   : a->convection == "central" ? cfd::Convection::Central
                                                : cfd::Convection::Upwind;
    o.nullspace = a->linear_solver == "nullspace";
    // Each LU factorization frees and allocates tens of MB. Above glibc's
    // mmap threshold every allocation is fresh pages from the kernel, zeroed
    // and faulted in one by one (a tenth of a 5 cm solve's time); keep freed
    // memory in the heap for the next factorization instead.
    mallopt(M_MMAP_THRESHOLD, 1 << 30);
    mallopt(M_TRIM_THRESHOLD, 1 << 30);
    const Map map = read_map(a->map);
    OutputDirectory out(a->out, "flow", {a->map});
    ProgressBar bar("flow");
    double first = 0.0;
    o.on_iteration = [&](int it, double mom, double cont) {
      const double r = std::max(mom, cont);
      if (it == 0) first = r;
      // Newton's progress: the fraction of the way from the first residual to the tolerance, in
      // log.
      const double done = std::log(first / r) / std::log(first / o.tolerance);
      std::ostringstream note;
      note.precision(2);
      note << "iteration " << it << ", residual " << std::scientific << r;
      bar.update(std::isfinite(done) ? done : 0.0, note.str());
    };
    cfd::FlowResult result = cfd::solve(map, o);
    bar.finish();
    cfd::write_flow(out.open(), map, result, o);
    out.commit();
    nlohmann::ordered_json j{{"ok", true}, {"map", a->map}, {"out", a->out}};
    j.update(cfd::summary_json(result.summary, result.wind, o));
    j.erase("residual_history");
    const cfd::FlowSummary& s = result.summary;
    std::ostringstream human;
    human.precision(3);
    human << "wrote " << a->out << "/{u,v,p}.npy, wind.json, wind.vti, wind.png: " << s.nx << " x "
          << s.ny << " cells, " << s.iterations << " Newton iterations (" << s.factorizations
          << " factorizations), residuals " << std::scientific << s.momentum_residual << " / "
          << s.continuity_residual << ", mass imbalance " << s.mass_imbalance << std::defaultfloat
          << ", max speed " << s.max_speed << " m/s, " << s.seconds << " s";
    report(j, human.str());
  });
}

}  // namespace plumekit::cli
