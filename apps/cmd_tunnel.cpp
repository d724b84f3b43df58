// `plumekit localize tunnel` and `plumekit evaluate tunnel`: seed 004's 3-D systems in its wind
// tunnel (run/tunnel_run.hpp): the 3-D STE, the 3-D surge-spiral and the 2-D surge-cast baseline.
#include <memory>
#include <optional>
#include <sstream>
#include <string>

#include "apps/cli.hpp"
#include "apps/commands.hpp"
#include "core/error.hpp"
#include "core/option_check.hpp"
#include "core/progress.hpp"
#include "core/seed.hpp"
#include "core/thread_pool.hpp"
#include "methods/option_tables.hpp"
#include "methods/registry.hpp"
#include "run/tunnel_job.hpp"
#include "run/tunnel_run.hpp"
#include "ste/option_tables.hpp"

namespace plumekit::cli {

namespace fs = std::filesystem;
using nlohmann::ordered_json;

namespace {

// "X,Y,Z" in metres; InputError naming `flag` otherwise.
Vec3 parse_point3(const std::string& text, const std::string& flag) {
  std::istringstream in(text);
  Vec3 p;
  char c1 = 0, c2 = 0;
  if (!(in >> p.x >> c1 >> p.y >> c2 >> p.z) || c1 != ',' || c2 != ',' || !(in >> std::ws).eof() ||
      !is_finite(p))
    throw InputError(flag + ": expected a point X,Y,Z in metres (e.g. 1,2,0.5), got '" + text +
                     "'");
  return p;
}

// --tunnel L,W,H
void set_tunnel_size(world::Tunnel& t, const std::string& text) {
  const Vec3 s = parse_point3(text, "--tunnel");
  t.length = s.x, t.width = s.y, t.height = s.z;
}

// The flags both commands share: the tunnel, its wind and plume, the sensor, the methods' main
// settings (docs/methods.md, "The 3-D tunnel").
void add_tunnel_options(CLI::App* cmd, run::TunnelOptions& o) {
  CLI::Option* size =
      cmd->add_option_function<std::string>(
             "--tunnel", [&o](const std::string& s) { set_tunnel_size(o.tunnel, s); },
             "Tunnel length, width, height L,W,H in metres (x downwind, z up)")
          ->default_str("10,4,2");
  // One flag, three fields: a message names the part that is wrong.
  for (const auto& [part, letter] :
       {std::pair{"length", "L"}, std::pair{"width", "W"}, std::pair{"height", "H"}})
    bind_field_label(cmd, std::string("tunnel.") + part,
                     size->get_name() + "'s " + part + " (" + letter + " of L,W,H)");
  bind_field(cmd,
             cmd->add_option("--wind-speed", o.tunnel.speed,
                             "The tunnel's uniform wind along +x, m/s (thesis: 0.2 or 0.9)"),
             "tunnel.wind")
      ->capture_default_str();
  bind_field(cmd,
             cmd->add_option("--release-rate", o.world.filament.release_rate,
                             "Release rate, concentration units * m^3/s (500: the thesis's 5 %, "
                             "1000: 10 %)"),
             "plume.release_rate")
      ->capture_default_str();
  bind_field(cmd,
             cmd->add_option("--noise", o.world.noise,
                             "Std of each gas reading's noise, concentration units"),
             "ste.world.noise")
      ->capture_default_str();
  add_gas_sensor_options(cmd, o.world.sensor, "The robot's");
  add_table_flags(cmd, o.search, methods::crosswind_search_option_table(),
                  {"tunnel.search.threshold"});
  add_table_flags(cmd, o, run::tunnel_option_table(),
                  {"tunnel.time_limit_s", "tunnel.start_downwind"});
  add_table_flags(cmd, o.ste, ste::ste3d_option_table(), {"tunnel.ste.max_samples"});
  bind_field(cmd,
             cmd->add_option("--sigma-m", o.ste.likelihood.sigma_m,
                             "ste-3d: the model error sigma_M (thesis: 30)"),
             "ste.likelihood.sigma_m")
      ->capture_default_str();
  bind_field(cmd,
             cmd->add_option("--sigma-rel", o.ste.likelihood.sigma_rel,
                             "ste-3d: model error relative to the predicted concentration "
                             "(0: the thesis's constant error)"),
             "ste.likelihood.sigma_rel")
      ->capture_default_str();
}

std::string method_help() {
  return methods::tunnel_methods_help();
}

void add_localize_tunnel(CLI::App* localize) {
  auto* cmd = localize->add_subcommand(
      "tunnel", "Find a gas source in seed 004's 3-D wind tunnel (3-D STE, surge-spiral, ...)");
  struct Args {
    std::string method = "ste-3d", source, start, out, animate;
    std::uint64_t seed = kDefaultSeed;
    run::TunnelOptions options;
  };
  auto a = std::make_shared<Args>();
  bind_field(cmd, cmd->add_option("--method", a->method, method_help()), "tunnel.method")
      ->capture_default_str();
  bind_field(cmd,
             cmd->add_option("--source", a->source,
                             "True source X,Y,Z in metres (default: random, 1 m from the inlet)"),
             "tunnel.source");
  bind_field(cmd,
             cmd->add_option("--start", a->start,
                             "Robot start X,Y,Z (default: random; trackers 10 m downwind)"),
             "tunnel.start");
  add_seed_flag(cmd, a->seed, "Seed of the plume, the chain, the walk and random points");
  cmd->add_option("--out,-o", a->out, "Write run.json and trajectory.png here");
  cmd->add_option("--animate", a->animate,
                  "Write a replay of the mission seen from above and from the side: FILE.mp4 (a "
                  "video) or FILE.png (an animated PNG); with --out, the run's replay files too, "
                  "for `plumekit replay` (docs/replay.md)");
  add_tunnel_options(cmd, a->options);
  add_common_flags(cmd);
  cmd->callback([a] {
    run::TunnelLocalizeRequest q;
    q.options = a->options;
    q.seed = a->seed;
    q.out = a->out;
    q.animate = a->animate;
    q.progress = !output().json;
    q.options.method = run::parse_tunnel_method(a->method);
    q.options.validate();  // before the points: of both mistakes, the options' is the one said
    if (!a->source.empty()) q.source = parse_point3(a->source, "--source");
    if (!a->start.empty()) q.start = parse_point3(a->start, "--start");
    const Report rep = run::localize_tunnel_job(q);
    report(rep.json, rep.text);
  });
}

void add_evaluate_tunnel(CLI::App* evaluate) {
  auto* cmd = evaluate->add_subcommand(
      "tunnel", "Evaluate seed 004's 3-D systems in its wind tunnel over random sources");
  struct Args {
    std::string methods = "ste-3d", out = "out/evaluate-tunnel";
    int runs = 10, threads = kDefaultThreads;
    std::uint64_t seed = kDefaultSeed;
    bool replays = false;
    run::TunnelOptions options;
  };
  auto a = std::make_shared<Args>();
  bind_field(
      cmd,
      cmd->add_option("--method", a->methods,
                      "NAME[,NAME...] or all: " + method_help() + "; several: each into OUT/NAME/"),
      "tunnel.method")
      ->capture_default_str();
  bind_field(cmd, cmd->add_option("--runs", a->runs, "Runs, each a random source and start"),
             "tunnel.runs")
      ->capture_default_str();
  add_threads_flag(cmd, a->threads, "tunnel.threads", "Runs in parallel (0: one per core)");
  add_seed_flag(cmd, a->seed, "Seed of plumes, chains, walks, sources and starts");
  cmd->add_option("--out,-o", a->out,
                  "Output folder (new, empty, or an earlier output, which is replaced): "
                  "runs.csv, summary.json, tracks.json, report.html, boxplot.png, "
                  "trajectory-median.png")
      ->capture_default_str();
  cmd->add_flag("--replays", a->replays,
                "Record every run's replay into replays/ (report.html plays them from above and "
                "from the side; `plumekit replay` draws one as a video); the runs take longer, "
                "their results are the same");
  add_tunnel_options(cmd, a->options);
  add_common_flags(cmd);
  cmd->callback([a] {
    run::TunnelEvaluateRequest q{
        a->options, run::parse_tunnel_methods(a->methods), a->runs, a->threads, a->seed, a->out};
    q.replays = a->replays;
    ProgressBar bar("evaluate tunnel");
    const Report rep = run::evaluate_tunnel_job(
        q, [&bar](double fraction, const std::string& note) { bar.update(fraction, note); });
    bar.finish();
    report(rep.json, rep.text);
  });
}

}  // namespace

void add_tunnel_commands(CLI::App& app) {
  add_localize_tunnel(app.get_subcommand("localize"));
  add_evaluate_tunnel(app.get_subcommand("evaluate"));
}

}  // namespace plumekit::cli
