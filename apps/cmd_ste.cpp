// plumekit localize / evaluate / demo: source term estimation with a
// simulated robot (ste/), one run, a whole evaluation, or the README's demo.
// Each flag is bound to a field of the library's options (run::SteOptions,
// run::EvaluationOptions, run::DemoOptions), whose defaults and checks are
// the only ones; this file binds and prints.
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <set>
#include <sstream>
#include <vector>

#include "apps/cli.hpp"
#include "apps/commands.hpp"
#include "cfd/wind_file.hpp"
#include "core/option_check.hpp"
#include "core/progress.hpp"
#include "methods/option_tables.hpp"
#include "run/demo.hpp"
#include "run/evaluate_job.hpp"
#include "run/evaluation.hpp"
#include "run/localize_job.hpp"
#include "run/option_tables.hpp"
#include "run/scenario.hpp"
#include "ste/option_tables.hpp"
#include "ste/surrogate_plume.hpp"
#include "surrogate/plume_network.hpp"
#include "world/option_tables.hpp"

namespace plumekit::cli {

namespace {

namespace fs = std::filesystem;
using nlohmann::ordered_json;

// `flag` bound to `field` with the field's value as the --help default.
template <typename T>
void bind_to(CLI::App* cmd, const std::string& flag, T& field, const std::string& help,
             const std::string& name) {
  bind_field(cmd, cmd->add_option(flag, field, help), name)->capture_default_str();
}

// The plume model, the CNN file, the likelihood: what depends on the model.
void add_model_options(CLI::App* cmd, run::SteOptions& o) {
  const OptionTable<run::SteOptions>& table = run::ste_option_table();
  add_table_flags(cmd, o, table, {"ste.model"});
  o.model_path = shipped_cnn().string();  // the library leaves where the shipped CNN is to us
  add_table_flags(cmd, o, table, {"ste.model_path"});
  resolve_cnn_names(cmd->get_option("--cnn"));
  resolve_cnn_names(add_deprecated_alias(cmd, "--model", "--cnn", o.model_path));
  add_table_flags(cmd, o.likelihood, run::ste_likelihood_option_table());
  add_table_flags(cmd, o, table, {"ste.source_cell", "ste.table_cell"});
  add_table_flags(cmd, o.physics.advection_diffusion, cfd::advection_diffusion_option_table(),
                  {"plume.diffusivity", "plume.decay_rate"});
  const std::string known = default_text(ste::physics_option_table().entry("ste.physics.scale_lo"));
  bind_field(cmd,
             bind_field(cmd,
                        cmd->add_option_function<std::string>(
                            "--release-scale",
                            [&o](const std::string& text) {
                              const Vec2 r = parse_point(text, "--release-scale");
                              o.physics.scale_lo = r.x;
                              o.physics.scale_hi = r.y;
                            },
                            "LO,HI: estimate the release rate as a scale in [LO, HI] of the "
                            "nominal 1000, marginalised in closed form (surrogate, physics; "
                            "default: known, " +
                                known + ")"),
                        "ste.physics.scale_lo"),
             "ste.physics.scale_hi");
  add_table_flags(cmd, o, table, {"ste.table_cache"});
}

// `text` as a number, for a flag that also takes a preset's name (handled by
// the caller); OptionError naming `field` and what it `expects` otherwise.
double number_or_preset(const std::string& text, const std::string& field,
                        const std::string& expects) {
  std::istringstream in(text);
  double value = 0.0;
  if (!(in >> value) || !(in >> std::ws).eof())
    throw OptionError(field, "expected " + expects + ", got '" + text + "'");
  return value;
}

// The simulated world and the robot's sensors in it.
void add_robot_world_options(CLI::App* cmd, run::SteOptions& o) {
  bind_to(cmd, "--release-rate", o.world.filament.release_rate,
          "The true source's release rate in the world, concentration units * m^2/s (the plume "
          "models' nominal is 1000; --release-scale lets STE estimate another)",
          "plume.release_rate");
  // First: the preset's callback runs before the flags that override its halves.
  add_table_flags(cmd, o, run::ste_option_table(), {"ste.protocol", "ste.success_radius"});
  add_table_flags(
      cmd, o.world, world::world_option_table(),
      {"ste.world.noise", "ste.world.speed", "ste.world.sample_s", "ste.world.sample_rate"});
  add_world_options(cmd, o.world.filament);
  add_gas_sensor_options(cmd, o.world.sensor, "The robot's");
  bind_field(cmd,
             cmd->add_option_function<std::string>(
                    "--wind-noise",
                    [&o](const std::string& text) {
                      o.world.wind_noise_from_table35 = text == "table35";
                      if (!o.world.wind_noise_from_table35)
                        o.world.wind_direction_noise_deg = number_or_preset(
                            text, "ste.world.wind_direction_noise", "degrees or table35");
                    },
                    "Anemometer direction error per stop: std in degrees, or table35 (seed 000, "
                    "Table 3.5, at the stop's length: 22.26 for 5 s, 14.02 for 20 s)")
                 ->type_name("DEG|table35")
                 ->default_str(default_text(
                     world::world_option_table().entry("ste.world.wind_direction_noise"))),
             "ste.world.wind_direction_noise");
  add_table_flags(cmd, o.world, world::world_option_table(), {"ste.world.wind_variance_noise"});
  bind_field(cmd,
             cmd->add_option_function<std::string>(
                    "--position-noise",
                    [&o](const std::string& text) {
                      const bool gps = text == "gps";
                      o.world.position_noise_per_fix = gps;
                      o.world.position_noise =
                          gps ? world::kGpsPositionNoise
                              : number_or_preset(text, "ste.world.position_noise", "metres or gps");
                    },
                    "Std per axis of the position recorded with each sample (stop): metres, or "
                    "gps (seed 000 Eq. 4.3: variance 1.17 m^2, so 1.08 m on each reading's fix; "
                    "the stop records their mean, 0.24 m for 20 readings)")
                 ->type_name("M|gps")
                 ->default_str(
                     default_text(world::world_option_table().entry("ste.world.position_noise"))),
             "ste.world.position_noise");
  add_table_flags(
      cmd, o.world, world::world_option_table(),
      {"ste.world.odometry_drift", "ste.world.rotor_disc", "ste.world.read_while_moving",
       "ste.world.adaptive_stop", "ste.world.stop_min_s", "ste.world.stop_tolerance"});
  add_table_flags(cmd, o, run::ste_option_table(),
                  {"ste.passing_window_s", "ste.path_scoring", "ste.approach"});
}

// A team of robots (seed 004 ch. 13; run/team.hpp).
void add_team_options(CLI::App* cmd, run::TeamOptions& t) {
  add_table_flags(cmd, t, run::team_option_table());
}

// The simulated world, the navigation, the stopping rule and the wind.
void add_run_options(CLI::App* cmd, run::SteOptions& o) {
  add_robot_world_options(cmd, o);
  add_table_flags(cmd, o.navigation, ste::navigation_option_table());
  add_table_flags(cmd, o, run::ste_option_table(), {"ste.margin"});
  add_table_flags(cmd, o.stop, ste::stop_option_table());
  add_table_flags(cmd, o.flow, cfd::flow_option_table(), {"flow.cell"});
  add_team_options(cmd, o.team);
}

void add_walk_options(CLI::App* cmd, run::MethodOptions& m);

// The localization method and the options of the seeds' methods (docs/methods.md).
// With `several` (evaluate), --method also takes a list or "all", which goes there.
void add_method_options(CLI::App* cmd, run::MethodOptions& m,
                        std::vector<std::string>* several = nullptr) {
  std::string names;
  for (const std::string& n : run::method_names())
    names += (names.empty() ? "" : ", ") + n;
  const std::string what =
      " (ste: plumekit's source term estimation; the others are the seeds' plume trackers and "
      "particle filters, docs/methods.md)";
  auto one = [&m](const std::string& s) { m.name = run::find_method(s).name; };
  auto list = [&m, several](const std::string& s) {
    *several = run::parse_method_list(s);
    m.name = several->front();
  };
  const std::string help =
      several ? "Localization method: " + names + what +
                    "; or several, NAME,NAME,... or all, sampling one world per run, each into "
                    "OUT/NAME/ (docs/design/evaluation.md, \"Several methods in one world\")"
              : "Localization method: " + names + what;
  CLI::Option* option = several ? cmd->add_option_function<std::string>("--method", list, help)
                                : cmd->add_option_function<std::string>("--method", one, help);
  bind_field(cmd, option->default_str(m.name), "ste.method");
  add_table_flags(cmd, m.tracking, methods::tracking_option_table());
  add_table_flags(cmd, m, methods::method_option_table(), {"tracking.max_steps"});
  add_table_flags(cmd, m.pf.filter, methods::particle_filter_option_table(), {"pf.particles"});
  add_table_flags(cmd, m.pf, methods::pf_method_option_table(),
                  {"pf.declare_iterations", "pf.declare_radius"});
  add_table_flags(cmd, m, methods::method_option_table(), {"pf.alpha", "pf.beta"});
  add_walk_options(cmd, m);
}

// The options of the APF, Lévy taxis and the local framework.
void add_walk_options(CLI::App* cmd, run::MethodOptions& m) {
  bind_field(cmd,
             cmd->add_option_function<std::string>(
                    "--apf-weights",
                    [&m](const std::string& text) {
                      std::istringstream in(text);
                      char c1 = 0, c2 = 0;
                      if (!(in >> m.apf.beta_m >> c1 >> m.apf.beta_v >> c2 >> m.apf.beta_c) ||
                          c1 != ',' || c2 != ',' || !(in >> std::ws).eof())
                        throw OptionError("apf.beta_c", "expected M,V,C, got '" + text + "'");
                    },
                    "APF: weights of the mean, variance and confidence terms, summing to 1 "
                    "(seed 000 ch. 8's best)")
                 ->type_name("M,V,C")
                 ->default_str(methods::default_weights()),
             "apf.beta_c");
  bind_field_label(cmd, "apf.beta_m", "--apf-weights' M");
  bind_field_label(cmd, "apf.beta_v", "--apf-weights' V");
  add_table_flags(cmd, m.apf, methods::apf_option_table(), {"apf.locality"});
  add_table_flags(cmd, m.levy, methods::levy_option_table());
  add_table_flags(cmd, m.local, methods::local_option_table(), {"local.budget", "local.map_size"});
}

void add_ste_options(CLI::App* cmd, run::SteOptions& o,
                     std::vector<std::string>* several_methods = nullptr) {
  add_method_options(cmd, o.method, several_methods);
  add_model_options(cmd, o);
  add_run_options(cmd, o);
}

// The JSON and text of a run, with the start's move when it was moved off an
// obstacle (points in the map's frame).
void report_run(Report r, const std::optional<Vec2>& requested, Vec2 used, bool moved) {
  if (requested && moved) {
    add_moved_start(r.json, *requested, used);
    r.text += "\n" + moved_start_text(*requested, used);
  }
  report(r.json, r.text);
}

// `localize`'s job, saying what to type when the surrogate does not fit the map.
run::LocalizeReport localize(const run::LocalizeRequest& request) {
  try {
    return run::localize_job(request);
  } catch (const surrogate::MapSizeError& e) {
    throw InputError(with_map_size_advice(e.what(), true));
  }
}

void add_localize(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "localize",
      "Find a gas source with a simulated robot (source term estimation, or any --method)");
  struct Args {
    std::string map, source, start, out, animate;
    std::uint64_t seed = kDefaultSeed;
    run::SteOptions ste;
  };
  auto a = std::make_shared<Args>();
  add_map_argument(cmd, a->map);
  // Required unless `localize tunnel` (apps/cmd_tunnel.cpp) is the command: checked below, as
  // CLI11's required() would refuse the subcommand. --help marks it as CLI11 marks required().
  bind_field(cmd,
             cmd->add_option("--source", a->source,
                             "True source X,Y in metres (simulated); required, except with "
                             "`localize tunnel`")
                 ->option_text("X,Y REQUIRED"),
             "ste.source");
  bind_field(cmd,
             cmd->add_option("--start", a->start, "Robot start X,Y (default: a random free point)"),
             "ste.start");
  add_seed_flag(cmd, a->seed, "Seed of the plume, noise and random start");
  cmd->add_option("--out,-o", a->out, "Write run.json, trajectory.png, posterior.png here");
  cmd->add_option("--animate", a->animate,
                  "Write a replay of the mission: FILE.mp4 (a video) or FILE.png (an animated "
                  "PNG); with --out, the run's replay files too, for `plumekit replay` "
                  "(docs/replay.md)")
      ->type_name("FILE");
  add_ste_options(cmd, a->ste);
  cmd->add_option("--wind", a->ste.wind_dir, cfd::kWindHelp)->check(CLI::ExistingDirectory);
  add_threads_flag(cmd, a->ste.threads, "ste.threads",
                   "Threads of the surrogate's table build (0: one per core)");
  add_common_flags(cmd);
  cmd->callback([a, cmd] {
    if (cmd->got_subcommand("tunnel")) return;  // `localize tunnel` did the work
    if (a->source.empty()) throw CLI::RequiredError("--source");
    // Points are typed in the map's frame (its file's coordinates).
    run::LocalizeRequest q;
    q.map = a->map;
    q.source = parse_point(a->source, "--source");
    q.seed = a->seed;
    q.ste = a->ste;
    q.out = a->out;
    if (!a->start.empty()) q.start = parse_point(a->start, "--start");
    q.animate = a->animate;
    q.progress = !output().json;
    const run::LocalizeReport r = localize(q);
    report_run(r.report, r.requested_start, r.start, r.start_moved);
  });
}

// Every flag of `evaluate` that shapes the results, as given or its default: what the parts
// of a --shard split must share (run::EvaluateRequest::result_options). Where the output goes, the
// threads, the table cache and the memory limit change no result; the map folder and the CNN are
// compared by their files' SHA-256, which the job adds.
ordered_json result_options(const CLI::App* cmd) {
  static const std::set<std::string> not_results{
      "--out",         "--shard", "--threads", "--json", "--max-memory",
      "--table-cache", "--help",  "--map-dir", "--cnn",  "--replays"};
  ordered_json j = ordered_json::object();
  for (const CLI::Option* opt : cmd->get_options()) {
    const std::string name = opt->get_name();
    if (not_results.count(name) || opt->get_group().empty()) continue;  // "": a hidden alias
    j[name] = opt->count() > 0 ? CLI::detail::join(opt->results(), " ") : opt->get_default_str();
  }
  return j;
}

void add_evaluate_merge(CLI::App* evaluate) {
  auto* cmd = evaluate->add_subcommand(
      "merge", "Join the parts of `evaluate --shard K/N` into one evaluation, verifying them");
  struct Args {
    std::string out;
    std::vector<std::string> parts;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("PARTS", a->parts, "Part folders (the --out of each `evaluate --shard K/N`)")
      ->required();
  cmd->add_option("--out,-o", a->out,
                  "Output folder (new, empty, or an earlier `evaluate` output, which is "
                  "replaced): report.html, runs.csv, summary.json, timings, tracks.json, box plots")
      ->required();
  add_common_flags(cmd);
  cmd->callback([a] {
    const Report rep =
        run::merge_job(std::vector<fs::path>(a->parts.begin(), a->parts.end()), a->out);
    report(rep.json, rep.text);
  });
}

struct EvaluateArgs {
  std::string map_dir, out = "out/evaluate";
  bool part = false, replays = false;
  run::EvaluationOptions eval;
  std::vector<std::string> methods;  // --method with several: one world per run
};

void run_evaluate(const EvaluateArgs& args, const CLI::App* cmd);

void add_evaluate(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "evaluate", "Localize every ground-truth source of every map N times; scores and pictures");
  auto a = std::make_shared<EvaluateArgs>();
  bind_field(
      cmd,
      cmd->add_option("--map-dir", a->map_dir, "Folder of map files with \"sources\" (*.json)"),
      "evaluation.map_dir");
  add_deprecated_alias(cmd, "--maps", "--map-dir", a->map_dir);
  add_table_flags(cmd, a->eval, run::evaluation_option_table());
  bind_field(cmd,
             cmd->add_option_function<std::string>(
                 "--shard",
                 [a](const std::string& k_of_n) {
                   a->eval.set_part(k_of_n);
                   a->part = true;
                 },
                 "K/N: only part K of N of the (map, source) pairs, into a part folder (then "
                 "`evaluate merge`)"),
             "evaluation.shard");
  add_seed_flag(cmd, a->eval.seed, "Seed of plumes, noise and starts");
  cmd->add_option("--out,-o", a->out,
                  "Output folder (new, empty, or an earlier `evaluate` output, which is "
                  "replaced): report.html, runs.csv, summary.json, timings, tracks.json, box "
                  "plots, trajectories/")
      ->capture_default_str();
  cmd->add_flag("--replays", a->replays,
                "Record every run's replay into replays/ (report.html plays them; `plumekit "
                "replay` draws one as a video); the runs take longer, their results are the same");
  add_ste_options(cmd, a->eval.ste, &a->methods);
  add_common_flags(cmd);
  add_evaluate_merge(cmd);
  cmd->callback([a, cmd] {
    // `evaluate merge` or `evaluate tunnel` did the work
    if (cmd->got_subcommand("merge") || cmd->got_subcommand("tunnel")) return;
    try {
      run_evaluate(*a, cmd);
    } catch (const surrogate::MapSizeError& e) {
      throw InputError(with_map_size_advice(e.what(), true));
    }
  });
}

// Evaluates the method or methods of `args` and writes each one's folder.
void run_evaluate(const EvaluateArgs& args, const CLI::App* cmd) {
  run::EvaluateRequest q{args.map_dir, args.out, args.eval, args.methods, args.part};
  q.replays = args.replays;
  if (args.part) q.result_options = result_options(cmd);
  ProgressBar bar("evaluate");
  const Report rep = run::evaluate_job(
      q, [&bar](double fraction, const std::string& note) { bar.update(fraction, note); });
  bar.finish();
  report(rep.json, rep.text);
}

void add_demo(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "demo", "Localize a gas source on a shipped test map and draw the run (under a minute)");
  struct Args {
    std::string out = "out/demo";
    run::DemoOptions demo;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("--out,-o", a->out,
                  "Where the pictures go: a new, empty, or earlier `demo` output folder")
      ->capture_default_str();
  add_seed_flag(cmd, a->demo.seed, "Seed of the plume and noise");
  add_ste_options(cmd, a->demo.ste);
  add_threads_flag(cmd, a->demo.ste.threads, "ste.threads",
                   "Threads of the surrogate's table build (0: one per core)");
  add_common_flags(cmd);
  cmd->callback([a, cmd] {
    run::DemoOptions& d = a->demo;
    const std::string note =
        cmd->get_option("--plume-model")->count() == 0 ? run::choose_demo_model(d.ste) : "";
    if (!note.empty() && !output().json) std::cerr << note << "\n";
    const run::LocalizeReport r = run::demo_job(d, data_dir() / "test-maps", a->out, note);
    report_run(r.report, r.requested_start, r.start, r.start_moved);
  });
}

}  // namespace

void add_ste_commands(CLI::App& app) {
  add_localize(app);
  add_evaluate(app);
  add_demo(app);
}

}  // namespace plumekit::cli
