// `plumekit localize tunnel` and `plumekit evaluate tunnel`: seed 004's 3-D systems in its wind
// tunnel (run/tunnel_run.hpp): the 3-D STE, the 3-D surge-spiral and the 2-D surge-cast baseline.
#include <memory>
#include <optional>
#include <sstream>
#include <string>

#include "apps/cli.hpp"
#include "apps/commands.hpp"
#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/option_check.hpp"
#include "core/output_target.hpp"
#include "core/progress.hpp"
#include "core/seed.hpp"
#include "core/statistics.hpp"
#include "core/thread_pool.hpp"
#include "map/map_render.hpp"
#include "methods/option_tables.hpp"
#include "run/tunnel_report.hpp"
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
  return "ste-3d (seed 004 ch. 11), surge-spiral (ch. 17) or surge-cast-2d (ch. 17's 2-D "
         "baseline at a fixed altitude)";
}

void add_localize_tunnel(CLI::App* localize) {
  auto* cmd = localize->add_subcommand(
      "tunnel", "Find a gas source in seed 004's 3-D wind tunnel (3-D STE, surge-spiral, ...)");
  struct Args {
    std::string method = "ste-3d", source, start, out;
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
  add_tunnel_options(cmd, a->options);
  add_common_flags(cmd);
  cmd->callback([a] {
    run::TunnelOptions& o = a->options;
    o.method = run::parse_tunnel_method(a->method);
    o.validate();
    std::optional<Vec3> source, start;
    if (!a->source.empty()) source = parse_point3(a->source, "--source");
    if (!a->start.empty()) start = parse_point3(a->start, "--start");
    std::optional<OutputDirectory> out;
    if (!a->out.empty()) out.emplace(a->out, "localize");
    const run::TunnelRun run = run::localize_tunnel(o, source, start, a->seed);
    ordered_json j{{"ok", true}, {"seed", a->seed}};
    j["settings"] = run::tunnel_settings(o);
    j.update(run::tunnel_run_json(run, false));
    std::string text = run::tunnel_run_line(run);
    if (out) {
      const fs::path& dir = out->open();
      ordered_json file = j;
      file.update(run::tunnel_run_json(run, true));
      write_file_atomic(dir / "run.json", file.dump(2) + "\n");
      write_png(run::draw_tunnel_run(run, o.tunnel, text), dir / "trajectory.png");
      out->commit();
      const fs::path d = a->out;
      j["out"] = {{"run", (d / "run.json").string()},
                  {"trajectory", (d / "trajectory.png").string()}};
      text += "\nwrote " + (d / "trajectory.png").string() + ", " + (d / "run.json").string();
    }
    report(j, text);
  });
}

// The run a picture of an evaluation shows: STE's of median error, a tracker's of median time.
std::size_t median_run(const std::vector<run::TunnelRun>& runs) {
  std::vector<double> key;
  for (const run::TunnelRun& r : runs)
    key.push_back(run::is_tracker(r.method) ? r.mission_s : r.error_m());
  const double m = median(key);
  std::size_t best = 0;
  for (std::size_t k = 1; k < key.size(); ++k)
    if (std::abs(key[k] - m) < std::abs(key[best] - m)) best = k;
  return best;
}

void add_evaluate_tunnel(CLI::App* evaluate) {
  auto* cmd = evaluate->add_subcommand(
      "tunnel", "Evaluate seed 004's 3-D systems in its wind tunnel over random sources");
  struct Args {
    std::string methods = "ste-3d", out = "out/evaluate-tunnel";
    int runs = 10, threads = kDefaultThreads;
    std::uint64_t seed = kDefaultSeed;
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
                  "runs.csv, summary.json, boxplot.png, trajectory-median.png")
      ->capture_default_str();
  add_tunnel_options(cmd, a->options);
  add_common_flags(cmd);
  cmd->callback([a] {
    const std::vector<run::TunnelMethod> methods = run::parse_tunnel_methods(a->methods);
    const bool several = methods.size() > 1;
    std::vector<run::TunnelOptions> each(methods.size(), a->options);
    for (std::size_t m = 0; m < methods.size(); ++m) {
      each[m].method = methods[m];
      each[m].validate();
    }
    // Several: OUT is one output written whole, each method's folder inside its own.
    std::optional<OutputDirectory> whole;
    if (several) whole.emplace(a->out, "evaluate");
    std::vector<fs::path> outs;
    std::vector<std::unique_ptr<OutputDirectory>> dirs;
    for (std::size_t m = 0; m < methods.size(); ++m) {
      const std::string name = to_string(methods[m]);
      outs.push_back(several ? fs::path(a->out) / name : fs::path(a->out));
      dirs.push_back(
          std::make_unique<OutputDirectory>(several ? whole->open() / name : outs[m], "evaluate"));
    }
    ordered_json j{{"ok", true}, {"seed", a->seed}, {"methods", ordered_json::array()}};
    std::string text;
    ProgressBar bar("evaluate tunnel");
    const int total = a->runs * static_cast<int>(methods.size());
    for (std::size_t m = 0; m < methods.size(); ++m) {
      const int before = a->runs * static_cast<int>(m);
      const std::vector<run::TunnelRun> runs =
          run::evaluate_tunnel(each[m], a->runs, a->seed, a->threads, [&](int done, int) {
            bar.update(static_cast<double>(before + done) / total,
                       std::to_string(before + done) + "/" + std::to_string(total) + " runs");
          });
      ordered_json summary{{"method", to_string(methods[m])}, {"seed", a->seed}};
      summary["settings"] = run::tunnel_settings(each[m]);
      summary.update(run::tunnel_summary(runs));
      const fs::path& dir = dirs[m]->open();
      write_file_atomic(dir / "runs.csv", run::tunnel_runs_csv(runs));
      write_file_atomic(dir / "summary.json", summary.dump(2) + "\n");
      const std::string name = to_string(methods[m]);
      write_png(run::draw_tunnel_box_plot(runs, name + ", " + std::to_string(runs.size()) +
                                                    " runs, wind " + compact(each[m].tunnel.speed) +
                                                    " m/s"),
                dir / "boxplot.png");
      const std::size_t k = median_run(runs);
      write_png(run::draw_tunnel_run(
                    runs[k], each[m].tunnel,
                    "run " + std::to_string(k) + " (median): " + run::tunnel_run_line(runs[k])),
                dir / "trajectory-median.png");
      dirs[m]->commit();
      j["methods"].push_back(summary);
      const ordered_json& s = summary;
      std::ostringstream line;
      line.precision(3);
      line << name << ": " << runs.size() << " runs, success " << 100.0 * s["success"].get<double>()
           << " %, median error " << s["median_error_m"].get<double>() << " m (z "
           << s["median_error_z_m"].get<double>() << " m), median distance "
           << s["median_distance_m"].get<double>() << " m, median time "
           << s["median_mission_s"].get<double>() << " s\n  wrote " << outs[m].string()
           << "/{runs.csv, summary.json, boxplot.png, trajectory-median.png}\n";
      text += line.str();
    }
    bar.finish();
    if (whole) whole->commit();
    report(j, text);
  });
}

}  // namespace

void add_tunnel_commands(CLI::App& app) {
  add_localize_tunnel(app.get_subcommand("localize"));
  add_evaluate_tunnel(app.get_subcommand("evaluate"));
}

}  // namespace plumekit::cli
