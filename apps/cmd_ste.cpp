// plumekit localize / evaluate / demo: source term estimation with a
// simulated robot (ste/), one run, a whole evaluation, or the README's demo.
// Each flag is bound to a field of the library's options (run::SteOptions,
// run::EvaluationOptions, run::DemoOptions), whose defaults and checks are
// the only ones; this file binds and prints.
#include <chrono>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <memory>
#include <optional>
#include <set>
#include <sstream>
#include <vector>

#include "apps/cli.hpp"
#include "apps/commands.hpp"
#include "cfd/wind_file.hpp"
#include "core/atomic_file.hpp"
#include "core/option_check.hpp"
#include "core/output_target.hpp"
#include "core/progress.hpp"
#include "core/sha256.hpp"
#include "map/map_json.hpp"
#include "methods/option_tables.hpp"
#include "run/demo.hpp"
#include "run/evaluation.hpp"
#include "run/evaluation_parts.hpp"
#include "run/option_tables.hpp"
#include "run/report.hpp"
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
  add_deprecated_alias(cmd, "--model", "--cnn", o.model_path);
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
  add_table_flags(cmd, o, run::ste_option_table(), {"ste.success_radius"});
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
  add_table_flags(cmd, o.world, world::world_option_table(),
                  {"ste.world.odometry_drift", "ste.world.rotor_disc"});
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
                    "OUT/NAME/ (docs/design/ste.md, \"Several methods in one world\")"
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

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

// The JSON and text of a run, with the start's move when it was moved off an
// obstacle (arena coordinates in, the map's frame out).
void report_run(Report r, const Map& map, const std::optional<Vec2>& requested, Vec2 used) {
  if (requested && (requested->x != used.x || requested->y != used.y)) {
    add_moved_start(r.json, map.to_frame(*requested), map.to_frame(used));
    r.text += "\n" + moved_start_text(map.to_frame(*requested), map.to_frame(used));
  }
  report(r.json, r.text);
}

// The scenario of `localize`, saying what to type when the surrogate does not fit the map.
run::Scenario scenario(const Map& map, const run::SteOptions& options) {
  try {
    return run::Scenario(map, options);
  } catch (const surrogate::MapSizeError& e) {
    throw InputError(with_map_size_advice(e.what(), true));
  }
}

void add_localize(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "localize",
      "Find a gas source with a simulated robot (source term estimation, or any --method)");
  struct Args {
    std::string map, source, start, out;
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
  add_ste_options(cmd, a->ste);
  cmd->add_option("--wind", a->ste.wind_dir, cfd::kWindHelp)->check(CLI::ExistingDirectory);
  add_threads_flag(cmd, a->ste.threads, "ste.threads",
                   "Threads of the surrogate's table build (0: one per core)");
  add_common_flags(cmd);
  cmd->callback([a, cmd] {
    if (cmd->got_subcommand("tunnel")) return;              // `localize tunnel` did the work
    const auto t_start = std::chrono::steady_clock::now();  // the summary accounts for all of it
    if (a->source.empty()) throw CLI::RequiredError("--source");
    // Points are typed in the map's frame (its file's coordinates).
    const Vec2 source_typed = parse_point(a->source, "--source");
    std::optional<Vec2> requested;
    if (!a->start.empty()) requested = parse_point(a->start, "--start");
    a->ste.validate();
    const Map map = read_map(a->map);
    const Vec2 source = map.from_frame(source_typed);
    if (requested) requested = map.from_frame(*requested);
    std::optional<OutputDirectory> out;
    if (!a->out.empty())
      out.emplace(a->out, "localize",
                  std::vector<fs::path>{a->map, a->ste.table_cache, a->ste.wind_dir});
    const run::Scenario sc = scenario(map, a->ste);
    sc.check_source(source);
    const std::uint64_t seed = world::run_seed(a->seed, 0, 0, 0);
    const Vec2 start =
        requested ? sc.check_start(*requested)
                  : sc.random_start(source, world::stream_seed(seed, world::SteStream::Start));
    const run::LocalizationResult r = sc.run(source, start, seed);
    // The pictures first, so that the time they take is in the summary's total.
    run::RunPictures pictures;
    if (out) pictures = run::write_run_pictures(sc, source, r, out->open());
    Report rep = run::run_report(sc, source, r, seconds_since(t_start));
    ordered_json j{{"ok", true},
                   {"map", provenance_path(a->map)},
                   {"plume_model", to_string(a->ste.model)},
                   {"seed", a->seed}};
    j.update(rep.json);
    rep.json = j;
    if (out) {
      const fs::path& dir = out->open();
      write_file_atomic(dir / "run.json", rep.json.dump(2) + "\n");
      out->commit();
      const fs::path o = a->out;
      rep.json["out"] = {{"run", (o / "run.json").string()},
                         {"trajectory", (o / "trajectory.png").string()}};
      rep.text += "\nwrote " + (o / "trajectory.png").string() + ", ";
      if (!pictures.posterior.empty()) {
        rep.json["out"]["posterior"] = (o / "posterior.png").string();
        rep.text += (o / "posterior.png").string() + ", ";
      }
      rep.text += (o / "run.json").string();
    }
    report_run(rep, map, requested, start);
  });
}

// Every flag of `evaluate` that shapes the results, as given or its default: what the parts
// of a --shard split must share. Where the output goes, the threads, the table cache and the
// memory limit change no result; the map folder and the CNN are compared by their files'
// SHA-256 (map_files_json, cnn_sha256) so that paths may differ between machines.
ordered_json result_options(const CLI::App* cmd, const run::EvaluationOptions& eo) {
  static const std::set<std::string> not_results{"--out",  "--shard",      "--threads",
                                                 "--json", "--max-memory", "--table-cache",
                                                 "--help", "--map-dir",    "--cnn"};
  ordered_json j = ordered_json::object();
  for (const CLI::Option* opt : cmd->get_options()) {
    const std::string name = opt->get_name();
    if (not_results.count(name) || opt->get_group().empty()) continue;  // "": a hidden alias
    j[name] = opt->count() > 0 ? CLI::detail::join(opt->results(), " ") : opt->get_default_str();
  }
  if (eo.ste.model == run::PlumeModelKind::Surrogate)
    j["cnn_sha256"] = sha256_file(eo.ste.model_path);
  return j;
}

// The part folder of `evaluate --shard K/N`: part.json, runs.csv, timings.csv, and the
// trajectory pictures of this part's median runs.
Report write_part(OutputDirectory& dir, const run::EvaluationResult& res,
                  const run::EvaluationOptions& eo, const run::PartIdentity& id,
                  const fs::path& out) {
  run::EvaluationFiles files;
  files.runs_csv = run::runs_csv(res);
  files.timings_csv = run::timings_csv(res);
  write_file_atomic(dir.open() / "runs.csv", files.runs_csv);
  write_file_atomic(dir.open() / "timings.csv", files.timings_csv);
  write_file_atomic(dir.open() / run::kPartFile, run::part_json(res, eo, id, files).dump(2) + "\n");
  dir.commit();
  const std::string part = std::to_string(eo.part_k) + "/" + std::to_string(eo.part_n);
  const ordered_json j{{"ok", true},           {"part", eo.part_k},
                       {"parts", eo.part_n},   {"runs", res.runs.size()},
                       {"wall_s", res.wall_s}, {"out", out.string()}};
  return {j, "evaluated part " + part + ": " + std::to_string(res.runs.size()) + " runs (pairs " +
                 std::to_string(res.pairs.first) + ".." + std::to_string(res.pairs.end) + " of " +
                 std::to_string(res.pairs.total) + " map sources)\nwrote " + out.string() +
                 "/{part.json, runs.csv, timings.csv, trajectories/}; join the parts with "
                 "`plumekit evaluate merge PART_DIR... --out DIR`"};
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
                  "replaced): runs.csv, summary.json, timings, box plots")
      ->required();
  add_common_flags(cmd);
  cmd->callback([a] {
    // Every part is verified before the output folder is touched.
    const std::vector<fs::path> parts(a->parts.begin(), a->parts.end());
    const run::MergedEvaluation m = run::merge_evaluation_parts(parts);
    OutputDirectory dir(a->out, "evaluate", parts);
    run::write_evaluation_files(dir.open(), m.result, m.files);
    dir.commit();
    Report rep = run::evaluation_report(m.result, m.settings, a->out, false);
    rep.json["parts"] = m.parts;
    rep.json["timings"] = m.files.timings;
    report(rep.json, "joined " + std::to_string(m.parts) + " parts\n" + rep.text);
  });
}

struct EvaluateArgs {
  std::string map_dir, out = "out/evaluate";
  bool part = false;
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
                  "replaced): runs.csv, summary.json, timings, box plots, trajectories/")
      ->capture_default_str();
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
  args.eval.validate();
  const run::MapFolder maps = run::read_map_folder(args.map_dir);
  const run::EvaluationOptions& eo = args.eval;
  // Several methods: each into OUT/NAME/, exactly what `--method NAME --out OUT/NAME` writes.
  const std::vector<std::string> kinds =
      args.methods.size() > 1 ? args.methods : std::vector<std::string>{eo.ste.method.name};
  const bool several = kinds.size() > 1;
  std::vector<run::EvaluationOptions> each(kinds.size(), eo);
  const std::vector<fs::path> inputs{args.map_dir, eo.ste.table_cache, eo.ste.model_path};
  // Several: OUT is one output, checked and locked like any before the work,
  // and written whole, so that no earlier method's results mix with these and
  // an interrupt leaves nothing; each method's folder inside is its own output.
  std::optional<OutputDirectory> whole;
  if (several) whole.emplace(args.out, "evaluate", inputs);
  std::vector<fs::path> outs;
  std::vector<std::unique_ptr<OutputDirectory>> dirs;
  for (std::size_t m = 0; m < kinds.size(); ++m) {
    each[m].ste.method.name = kinds[m];
    const std::string name = kinds[m];
    outs.push_back(several ? fs::path(args.out) / name : fs::path(args.out));
    dirs.push_back(std::make_unique<OutputDirectory>(several ? whole->open() / name : outs[m],
                                                     "evaluate", inputs));
  }
  std::vector<run::AfterMap> pictures;
  for (std::size_t m = 0; m < kinds.size(); ++m)
    pictures.push_back(run::trajectory_pictures(dirs[m]->open(), maps.picture_names));
  ProgressBar bar("evaluate");
  const std::string per_run =
      several ? " runs of " + std::to_string(kinds.size()) + " methods" : " runs";
  const std::vector<run::EvaluationResult> results = run::evaluate_methods(
      maps.maps, eo, kinds,
      [&](int done, int total) {
        bar.update(static_cast<double>(done) / total,
                   std::to_string(done) + "/" + std::to_string(total) + per_run);
      },
      [&](std::size_t m, const run::Scenario& sc, const std::vector<run::RunRecord>& records) {
        pictures[m](sc, records);
      });
  bar.finish();
  std::vector<Report> reports;
  for (std::size_t m = 0; m < kinds.size(); ++m) {
    const run::EvaluationResult& res = results[m];
    const ordered_json settings = run::evaluation_settings(each[m], args.map_dir);
    if (args.part) {
      ordered_json options = result_options(cmd, each[m]);
      options["--method"] = kinds[m];  // as the part of a single method
      const run::PartIdentity id{settings, options, run::map_files_json(maps)};
      reports.push_back(write_part(*dirs[m], res, each[m], id, outs[m]));
      continue;
    }
    Report rep = run::evaluation_report(res, settings, outs[m]);
    run::write_evaluation_files(
        dirs[m]->open(), res,
        {run::runs_csv(res), run::timings_csv(res), rep.json, run::evaluation_timings(res)});
    dirs[m]->commit();
    // On stdout the times go with the summary (they are apart only in the files).
    rep.json["timings"] = run::evaluation_timings(res);
    reports.push_back(rep);
  }
  if (!several) return report(reports.front().json, reports.front().text);
  whole->commit();
  // One total: the methods ran together, each run's plume simulated once for all of them.
  double wind_s = 0;
  for (const run::MapReport& mr : results.front().maps)
    wind_s += mr.wind_s;
  ordered_json j{{"ok", true}, {"methods", ordered_json::array()}};
  std::string text;
  for (std::size_t m = 0; m < kinds.size(); ++m) {
    j["methods"].push_back({{"method", kinds[m]},
                            {"model_build_s", results[m].model_build_s()},
                            {"decisions_s", results[m].decisions_s},
                            {"result", reports[m].json}});
    text += std::string(m ? "\n\n" : "") + "== " + kinds[m] + " ==\n" + reports[m].text;
  }
  j["wall_s"] = results.front().wall_s;
  j["wind_s"] = wind_s;
  std::ostringstream total;
  total << std::fixed << std::setprecision(1) << "\n\nall " << kinds.size() << " methods in "
        << results.front().wall_s << " s (wall clock; wind " << wind_s
        << " s, then every run's plume once for all the methods)";
  report(j, text + total.str());
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
    const auto t_start = std::chrono::steady_clock::now();  // the summary accounts for all of it
    run::DemoOptions& d = a->demo;
    const std::string note =
        cmd->get_option("--plume-model")->count() == 0 ? run::choose_demo_model(d.ste) : "";
    if (!note.empty() && !output().json) std::cerr << note << "\n";
    d.ste.validate();
    const fs::path map_file = data_dir() / "test-maps" / d.map_file;
    const Map map = read_map(map_file);
    OutputDirectory out(a->out, "demo", {map_file});
    const run::Scenario sc(map, d.ste);
    const Vec2 source = map.sources.at(d.source_index);
    const Vec2 requested = map.from_frame(d.start);
    const Vec2 start = sc.check_start(requested);
    const run::LocalizationResult r = sc.run(source, start, world::run_seed(d.seed, 0, 0, 0));
    const bool posterior = !run::write_run_pictures(sc, source, r, out.open()).posterior.empty();
    out.commit();
    const fs::path traj = fs::path(a->out) / "trajectory.png",
                   post = fs::path(a->out) / "posterior.png";
    Report rep = run::run_report(sc, source, r, seconds_since(t_start));
    ordered_json j{
        {"ok", true}, {"map", provenance_path(map_file)}, {"plume_model", to_string(d.ste.model)}};
    if (!note.empty()) j["note"] = note;
    j.update(rep.json);
    j["out"] = {{"trajectory", traj.string()}};
    rep.text += "\npictures: " + traj.string() + " (trajectory)";
    if (posterior) {
      j["out"]["posterior"] = post.string();
      rep.text += ", " + post.string() + " (posterior)";
    }
    rep.json = j;
    report_run(rep, map, requested, start);
  });
}

}  // namespace

void add_ste_commands(CLI::App& app) {
  add_localize(app);
  add_evaluate(app);
  add_demo(app);
}

}  // namespace plumekit::cli
