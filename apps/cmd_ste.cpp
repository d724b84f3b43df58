// plumekit localize / evaluate / demo: source term estimation with a
// simulated robot (ste/), one run, a whole evaluation, or the README's demo.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <optional>
#include <sstream>

#include "apps/cli.hpp"
#include "apps/commands.hpp"
#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/map_json.hpp"
#include "core/map_render.hpp"
#include "core/output_target.hpp"
#include "core/progress.hpp"
#include "ste/evaluation.hpp"
#include "ste/render.hpp"
#include "ste/scenario.hpp"

namespace plumekit::cli {

namespace {

namespace fs = std::filesystem;
using nlohmann::ordered_json;

std::string fmt(double v, int digits = 2) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(digits) << v;
  return s.str();
}

std::string fmt(Vec2 p) {
  return "(" + fmt(p.x) + ", " + fmt(p.y) + ")";
}

// The demo: a test map whose obstacles bend the plume, a source whose plume they bend,
// a start upwind.
constexpr const char* kDemoMap = "test-4-l-shape.json";
constexpr int kDemoSource = 4;  // (2.23, 2.51): upwind of the L, its plume bends over it
const Vec2 kDemoStart{1.0, 1.0};

fs::path shipped_model() {
  return data_dir() / "models" / "plume-unet.pkcnn";
}

// The options every STE command shares.
struct SteArgs {
  std::string plume_model = "surrogate";
  std::string model;
  // sigma_M and sigma_std unset (< 0): ste::default_likelihood of the plume model.
  double sigma_m = -1.0, sigma_d = 0.0, sigma_rel = 0.0, noise = 0.0, speed = 0.5;
  double sigma_std = -1.0;
  double alpha = 0.5, beta = 0.75, step = 0.5, margin = 0.15;
  double source_cell = 0.0;
  CLI::Option* source_cell_given = nullptr;  // unset: the model's default grid
  int max_samples = 50, lattice = 2;
  std::string reward = "expected";
  std::string table_cache, release_scale;
};

void add_ste_options(CLI::App* cmd, SteArgs& a) {
  bind_field(
      cmd,
      cmd->add_option("--plume-model", a.plume_model, "surrogate (the CNN), gaussian or physics"),
      "ste.model")
      ->capture_default_str();
  cmd->add_option("--model", a.model,
                  "Surrogate model file (default: data/models/plume-unet.pkcnn)");
  bind_field(cmd,
             cmd->add_option(
                 "--sigma-m", a.sigma_m,
                 "Model error sigma_M, concentration units (default: 200 for the surrogate, "
                 "about the shipped model's RMSE on the test maps; 30 for gaussian and physics, "
                 "the thesis's)"),
             "ste.likelihood.sigma_m")
      ->check(CLI::NonNegativeNumber);
  bind_field(
      cmd,
      cmd->add_option("--sigma-d", a.sigma_d, "Measurement error sigma_D, concentration units"),
      "ste.likelihood.sigma_d")
      ->capture_default_str();
  bind_field(
      cmd,
      cmd->add_option("--sigma-rel", a.sigma_rel,
                      "Model error relative to the predicted concentration, added in quadrature to "
                      "sigma_M (default 0: the thesis's constant error)"),
      "ste.likelihood.sigma_rel")
      ->check(CLI::NonNegativeNumber);
  bind_field(cmd,
             cmd->add_option(
                 "--sigma-std", a.sigma_std,
                 "Model error in units of the surrogate's predicted std of the readings, added "
                 "in quadrature (default: 2 for the surrogate; the other models predict no std)"),
             "ste.likelihood.sigma_std")
      ->check(CLI::NonNegativeNumber);
  bind_field(cmd,
             cmd->add_option("--noise", a.noise, "Sensor noise std per 10 Hz reading (simulated)"),
             "ste.world.noise")
      ->capture_default_str();
  bind_field(cmd, cmd->add_option("--speed", a.speed, "Robot speed, m/s"), "ste.world.speed")
      ->capture_default_str();
  bind_field(cmd,
             cmd->add_option("--alpha", a.alpha, "Weight of the KL move against the source move"),
             "ste.navigation.alpha")
      ->capture_default_str();
  bind_field(
      cmd,
      cmd->add_option("--beta", a.beta, "Weight of the posterior against the inverse distance"),
      "ste.navigation.beta")
      ->capture_default_str();
  bind_field(cmd, cmd->add_option("--step", a.step, "Candidate lattice spacing, m"),
             "ste.navigation.step")
      ->capture_default_str();
  bind_field(cmd,
             cmd->add_option("--lattice", a.lattice,
                             "Candidates up to this many steps per axis: (2 L + 1)^2 - 1 of them"),
             "ste.navigation.lattice")
      ->capture_default_str();
  cmd->add_option("--reward", a.reward,
                  "Candidate score: kl (the thesis's, at the expected source) or expected (the "
                  "expected information gain over the posterior's sources)")
      ->capture_default_str();
  bind_field(cmd, cmd->add_option("--margin", a.margin, "Planner clearance from obstacles, m"),
             "ste.margin")
      ->capture_default_str();
  bind_field(cmd, cmd->add_option("--max-samples", a.max_samples, "Stop after this many samples"),
             "ste.stop.max_samples")
      ->capture_default_str();
  bind_field(
      cmd,
      bind_field(cmd,
                 cmd->add_option(
                     "--release-scale", a.release_scale,
                     "LO,HI: estimate the release rate as a scale in [LO, HI] of the nominal 1000, "
                     "marginalised in closed form (surrogate, physics; default: known, 1)"),
                 "ste.physics.scale_lo"),
      "ste.physics.scale_hi");
  a.source_cell_given = cmd->add_option(
      "--source-cell", a.source_cell,
      "Candidate source grid, m (surrogate, physics; default: 0.2 for the surrogate, "
      "0.1 for physics)");
  bind_field(cmd, a.source_cell_given, "ste.surrogate_cell");
  bind_field(cmd, a.source_cell_given, "ste.physics.source_cell");
  cmd->add_option("--table-cache", a.table_cache,
                  "Directory caching surrogate tables (keyed by map and model hashes)");
}

// Binds the flags to the options; the library checks every value (SteOptions::validate).
ste::SteOptions to_options(const SteArgs& a) {
  ste::SteOptions o;
  o.model = ste::parse_plume_model_kind(a.plume_model);
  const ste::LikelihoodOptions defaults = ste::default_likelihood(o.model);
  // -1: not given (a NaN given is kept, for validate() to refuse).
  o.likelihood.sigma_m = a.sigma_m == -1.0 ? defaults.sigma_m : a.sigma_m;
  o.likelihood.sigma_d = a.sigma_d;
  o.likelihood.sigma_rel = a.sigma_rel;
  if (a.sigma_std > 0.0 && o.model != ste::PlumeModelKind::Surrogate)
    throw InputError("--sigma-std: only the surrogate predicts the std of the readings");
  o.likelihood.sigma_std = a.sigma_std == -1.0 ? defaults.sigma_std : a.sigma_std;
  o.world.noise = a.noise;
  o.world.speed = a.speed;
  o.navigation.alpha = a.alpha;
  o.navigation.beta = a.beta;
  o.navigation.step = a.step;
  o.navigation.lattice = a.lattice;
  if (a.reward == "kl")
    o.navigation.reward = ste::NavigationOptions::Reward::Kl;
  else if (a.reward == "expected")
    o.navigation.reward = ste::NavigationOptions::Reward::ExpectedGain;
  else
    throw InputError("--reward: unknown reward '" + a.reward + "' (kl or expected)");
  o.margin = a.margin;
  o.stop.max_samples = a.max_samples;
  o.table_cache = a.table_cache;
  if (a.source_cell_given && a.source_cell_given->count() > 0) {
    if (o.model == ste::PlumeModelKind::Gaussian)
      throw InputError(
          "--source-cell: only the surrogate and physics models have a source grid (the Gaussian "
          "plume's MH runs on the bins)");
    o.surrogate_cell = a.source_cell;
    o.physics.source_cell = a.source_cell;
  }
  if (!a.release_scale.empty()) {
    const Vec2 r = parse_point(a.release_scale, "--release-scale");
    o.physics.scale_lo = r.x;
    o.physics.scale_hi = r.y;
  }
  if (o.model == ste::PlumeModelKind::Surrogate) {
    o.model_path = a.model.empty() ? shipped_model().string() : a.model;
    if (!fs::exists(o.model_path))
      throw InputError("--model: " + o.model_path +
                       " not found (train one, see surrogate/README.md, or use --plume-model "
                       "physics or gaussian)");
  }
  o.validate();
  return o;
}

// The candidate source grid of a table model; null for the Gaussian plume (MH on the bins).
ordered_json source_cell_json(const ste::SteOptions& o) {
  switch (o.model) {
    case ste::PlumeModelKind::Surrogate:
      return o.surrogate_cell;
    case ste::PlumeModelKind::Physics:
      return o.physics.source_cell;
    case ste::PlumeModelKind::Gaussian:
      break;
  }
  return nullptr;
}

struct Pictures {
  fs::path trajectory, posterior;
};

// Writes trajectory.png and posterior.png for one run into dir.
Pictures draw_run(const ste::Scenario& sc, Vec2 source, const ste::LocalizationResult& r,
                  const fs::path& dir, const std::string& label) {
  Pictures p{dir / "trajectory.png", dir / "posterior.png"};
  const double err = norm(r.estimate - source);
  std::string title = sc.map().name + ": " + label + ", " + std::to_string(r.samples) +
                      " samples, " + fmt(r.distance_m, 1) + " m, error " + fmt(err) + " m (" +
                      r.stopped_by + ")";
  write_png(ste::draw_trajectory(sc.map(), sc.mean_plume(source), r, source, title), p.trajectory);
  write_png(ste::draw_posterior(sc.map(), r.posterior, source, r.estimate,
                                sc.map().name + ": final posterior (" + label + ")"),
            p.posterior);
  return p;
}

ordered_json run_json(const ste::Scenario& sc, Vec2 source, const ste::LocalizationResult& r) {
  ordered_json steps = ordered_json::array();
  for (const ste::Step& s : r.steps)
    steps.push_back({{"position", point_json(s.position)},
                     {"value", s.value},
                     {"time_s", s.time_s},
                     {"distance_m", s.distance_m},
                     {"estimate", point_json(s.estimate)},
                     {"entropy", s.entropy},
                     {"compute_s", s.compute_s}});
  ordered_json expected = ordered_json::object();
  const auto& params = sc.model().parameters();
  for (std::size_t k = 0; k < params.size() && k < r.expected.size(); ++k)
    expected[params[k].name] = r.expected[k];
  return {{"estimate", point_json(r.estimate)},
          {"error_m", norm(r.estimate - source)},
          {"samples", r.samples},
          {"distance_m", r.distance_m},
          {"compute_s", r.compute_s},
          {"stopped_by", r.stopped_by},
          {"median_step_s", r.median_step_s},
          {"mission_s", r.time_s},
          {"map_estimate", point_json(r.map)},
          {"source_cell", source_cell_json(sc.options())},
          {"expected_parameters", expected},
          {"entropy", r.posterior.entropy},
          {"max_entropy", r.posterior.max_entropy},
          {"start", point_json(r.start)},
          {"source", point_json(source)},
          {"wind_s", sc.wind_seconds()},
          {"table_build_s", sc.model_seconds()},
          {"steps", steps}};
}

std::string run_text(const ste::Scenario& sc, Vec2 source, const ste::LocalizationResult& r) {
  std::ostringstream h;
  h << sc.map().name << ", " << ste::to_string(sc.options().model) << " plume model: source "
    << fmt(source) << ", start " << fmt(r.start) << "\n"
    << "estimate " << fmt(r.estimate) << ", error " << fmt(norm(r.estimate - source)) << " m after "
    << r.samples << " samples and " << fmt(r.distance_m, 1) << " m (stopped by " << r.stopped_by
    << ")\ncompute " << fmt(r.compute_s, 3) << " s in all, median "
    << fmt(r.median_step_s * 1000, 1) << " ms per decision step; wind " << fmt(sc.wind_seconds(), 1)
    << " s, model build " << fmt(sc.model_seconds(), 1) << " s";
  return h.str();
}

// The run of a map whose error is the median one: its typical trajectory.
const ste::RunRecord& median_run(const std::vector<ste::RunRecord>& runs) {
  std::vector<const ste::RunRecord*> sorted;
  for (const ste::RunRecord& r : runs)
    sorted.push_back(&r);
  std::stable_sort(sorted.begin(), sorted.end(),
                   [](auto* a, auto* b) { return a->error_m < b->error_m; });
  return *sorted[(sorted.size() - 1) / 2];
}

ordered_json stats_json(const ste::Stats& s) {
  return {{"runs", s.runs},
          {"median_error_m", s.median_error_m},
          {"mean_error_m", s.mean_error_m},
          {"success_0_5m", s.success_0_5},
          {"success_1_0m", s.success_1_0},
          {"median_samples", s.median_samples},
          {"median_distance_m", s.median_distance_m},
          {"median_step_compute_s", s.median_step_s},
          {"entropy_stops", s.entropy_stops}};
}

}  // namespace

void add_ste_commands(CLI::App& app) {
  // ---- localize ------------------------------------------------------------
  {
    auto* cmd = app.add_subcommand(
        "localize", "Find a gas source with a simulated robot (source term estimation)");
    struct Args {
      std::string map = default_map().string(), source, start, out;
      std::uint64_t seed = 1;
      SteArgs ste;
    };
    auto a = std::make_shared<Args>();
    cmd->add_option("MAP", a->map, "Map file (JSON)")->capture_default_str();
    bind_field(cmd, cmd->add_option("--source", a->source, "True source X,Y in metres (simulated)"),
               "ste.source")
        ->required();
    bind_field(
        cmd, cmd->add_option("--start", a->start, "Robot start X,Y (default: a random free point)"),
        "ste.start");
    cmd->add_option("--seed", a->seed, "Seed of the plume, noise and random start")
        ->capture_default_str();
    cmd->add_option("--out,-o", a->out, "Write run.json, trajectory.png, posterior.png here");
    add_ste_options(cmd, a->ste);
    add_common_flags(cmd);
    cmd->callback([a] {
      const Vec2 source = parse_point(a->source, "--source");
      const Vec2 start_arg = a->start.empty() ? Vec2{} : parse_point(a->start, "--start");
      const ste::SteOptions options = to_options(a->ste);
      const Map map = read_map(a->map);
      std::optional<OutputDirectory> out;
      if (!a->out.empty())
        out.emplace(a->out, "localize", std::vector<fs::path>{a->map, a->ste.table_cache});
      const ste::Scenario sc(map, options);
      sc.check_source(source);
      const std::uint64_t seed = ste::run_seed(a->seed, 0, 0, 0);
      const Vec2 start =
          a->start.empty() ? sc.random_start(source, seed ^ 0xA5A5) : sc.check_start(start_arg);
      const ste::LocalizationResult r = sc.run(source, start, seed);
      ordered_json j{{"ok", true},
                     {"map", provenance_path(a->map)},
                     {"plume_model", ste::to_string(options.model)},
                     {"seed", a->seed}};
      j.update(run_json(sc, source, r));
      std::string human = run_text(sc, source, r);
      if (out) {
        const fs::path& dir = out->open();
        draw_run(sc, source, r, dir, ste::to_string(options.model));
        write_file_atomic(dir / "run.json", j.dump(2) + "\n");
        out->commit();
        const fs::path o = a->out;
        j["out"] = {{"run", (o / "run.json").string()},
                    {"trajectory", (o / "trajectory.png").string()},
                    {"posterior", (o / "posterior.png").string()}};
        human += "\nwrote " + (o / "trajectory.png").string() + ", " +
                 (o / "posterior.png").string() + ", " + (o / "run.json").string();
      }
      report(j, human);
    });
  }

  // ---- evaluate ------------------------------------------------------------
  {
    auto* cmd = app.add_subcommand(
        "evaluate", "Localize every ground-truth source of every map N times; scores and pictures");
    struct Args {
      std::string maps, out = "out/evaluate";
      int runs = 3, threads = 2, sources = 0;
      std::uint64_t seed = 1;
      SteArgs ste;
    };
    auto a = std::make_shared<Args>();
    cmd->add_option("--maps", a->maps, "Directory of map files with \"sources\" (*.json)")
        ->required();
    bind_field(
        cmd, cmd->add_option("--runs", a->runs, "Runs per source, from seeded random free starts"),
        "evaluation.runs")
        ->capture_default_str();
    bind_field(cmd, cmd->add_option("--threads", a->threads, "Runs in parallel"),
               "evaluation.threads")
        ->capture_default_str();
    bind_field(cmd,
               cmd->add_option("--sources", a->sources,
                               "Only the first K sources of each map (0: all; a labelled subset)"),
               "evaluation.sources")
        ->capture_default_str();
    cmd->add_option("--seed", a->seed, "Seed of plumes, noise and starts")->capture_default_str();
    cmd->add_option("--out,-o", a->out,
                    "Output folder (new, empty, or an earlier `evaluate` output, which is "
                    "replaced): runs.csv, summary.json, box plots, trajectories/")
        ->capture_default_str();
    add_ste_options(cmd, a->ste);
    add_common_flags(cmd);
    cmd->callback([a] {
      ste::EvaluationOptions eo;
      eo.ste = to_options(a->ste);
      eo.runs = a->runs;
      eo.threads = a->threads;
      eo.sources = a->sources;
      eo.seed = a->seed;
      eo.validate();
      if (!fs::is_directory(a->maps))
        throw InputError("--maps: " + a->maps + " is not a directory");
      std::vector<fs::path> files;
      for (const auto& e : fs::directory_iterator(a->maps))
        if (e.path().extension() == ".json") files.push_back(e.path());
      std::sort(files.begin(), files.end());
      if (files.empty()) throw InputError("--maps: no *.json map files in " + a->maps);
      std::vector<Map> maps;
      for (const fs::path& f : files)
        maps.push_back(read_map(f));
      // Pictures are named after the map files, never after the names inside them.
      std::vector<std::string> taken, picture_names;
      for (const fs::path& f : files)
        picture_names.push_back(safe_file_name(f.stem().string(), taken) + ".png");

      OutputDirectory dir(a->out, "evaluate", {a->maps, a->ste.table_cache, a->ste.model});
      fs::create_directories(dir.open() / "trajectories");
      ProgressBar bar("evaluate");
      const std::string label = ste::to_string(eo.ste.model);
      const ste::EvaluationResult res = ste::evaluate(
          maps, eo,
          [&](int done, int total) {
            bar.update(static_cast<double>(done) / total,
                       std::to_string(done) + "/" + std::to_string(total) + " runs");
          },
          [&](const ste::Scenario& sc, const std::vector<ste::RunRecord>& runs) {
            const ste::RunRecord& r = median_run(runs);
            const std::string title = sc.map().name + ": " + label + ", source S" +
                                      std::to_string(r.source_index) + " run " +
                                      std::to_string(r.run) + " (median error " + fmt(r.error_m) +
                                      " m, " + std::to_string(r.samples) + " samples)";
            write_png(
                ste::draw_trajectory(sc.map(), sc.mean_plume(r.source), r.result, r.source, title),
                dir.open() / "trajectories" / picture_names.at(r.map_index));
          });
      bar.finish();

      std::vector<std::vector<double>> errors, samples;
      std::vector<std::string> labels;
      ordered_json per_map = ordered_json::array();
      for (std::size_t m = 0; m < res.maps.size(); ++m) {
        const ste::MapReport& mr = res.maps[m];
        ordered_json j{{"map", mr.name}};
        j.update(stats_json(mr.stats));
        j["wind_s"] = mr.wind_s;
        j["table_build_s"] = mr.table_build_s;
        j["wall_s"] = mr.wall_s;
        per_map.push_back(j);
        errors.emplace_back();
        samples.emplace_back();
        for (const ste::RunRecord& r : res.runs)
          if (r.map_index == static_cast<int>(m)) {
            errors.back().push_back(r.error_m);
            samples.back().push_back(r.samples);
          }
        labels.push_back(std::to_string(m));
      }
      ordered_json summary{
          {"ok", true},
          {"maps_dir", provenance_path(a->maps)},
          {"plume_model", label},
          {"runs_per_source", eo.runs},
          {"sources_per_map", eo.sources > 0 ? ordered_json(eo.sources) : ordered_json("all")},
          {"seed", eo.seed},
          {"threads", eo.threads},
          {"sigma_m", eo.ste.likelihood.sigma_m},
          {"sigma_rel", eo.ste.likelihood.sigma_rel},
          {"sigma_std", eo.ste.likelihood.sigma_std},
          {"source_cell", source_cell_json(eo.ste)},
          {"noise", eo.ste.world.noise},
          {"overall", stats_json(res.overall)},
          {"maps", per_map},
          {"wall_s", res.wall_s}};
      write_file_atomic(dir.open() / "runs.csv", ste::runs_csv(res));
      write_file_atomic(dir.open() / "summary.json", summary.dump(2) + "\n");
      write_png(ste::draw_box_plot(errors, labels, "error [m]",
                                   "STE (" + label + ") localization error per test map", 0.5),
                dir.open() / "boxplot-error.png");
      write_png(ste::draw_box_plot(samples, labels, "samples",
                                   "STE (" + label + ") samples per test map"),
                dir.open() / "boxplot-samples.png");
      dir.commit();

      std::ostringstream h;
      h << "evaluated " << res.runs.size() << " runs (" << maps.size() << " maps, " << label
        << " plume model) in " << fmt(res.wall_s, 1) << " s\n";
      h << std::left << std::setw(22) << "map"
        << " median_err  mean_err  ok@0.5  ok@1.0  samples"
        << "  dist_m  step_ms  table_s\n";
      auto line = [&](const std::string& name, const ste::Stats& s, double table) {
        h << std::left << std::setw(22) << name << std::right << std::setw(11)
          << fmt(s.median_error_m) << std::setw(10) << fmt(s.mean_error_m) << std::setw(8)
          << fmt(100 * s.success_0_5, 0) + "%" << std::setw(8) << fmt(100 * s.success_1_0, 0) + "%"
          << std::setw(9) << fmt(s.median_samples, 0) << std::setw(8) << fmt(s.median_distance_m, 1)
          << std::setw(9) << fmt(1000 * s.median_step_s, 1) << std::setw(9)
          << (table >= 0 ? fmt(table, 1) : std::string("-")) << "\n";
      };
      for (const ste::MapReport& mr : res.maps)
        line(mr.name, mr.stats, mr.table_build_s);
      line("overall", res.overall, -1);
      h << "wrote " << a->out << "/{runs.csv, summary.json, boxplot-error.png, "
        << "boxplot-samples.png, trajectories/}";
      report(summary, h.str());
    });
  }

  // ---- demo ------------------------------------------------------------------
  {
    auto* cmd = app.add_subcommand(
        "demo", "Localize a gas source on a shipped test map and draw the run (under a minute)");
    struct Args {
      std::string out = "out/demo", plume_model;
    };
    auto a = std::make_shared<Args>();
    cmd->add_option("--out,-o", a->out,
                    "Where the pictures go: a new, empty, or earlier `demo` output folder")
        ->capture_default_str();
    bind_field(cmd,
               cmd->add_option(
                   "--plume-model", a->plume_model,
                   "surrogate, gaussian or physics (default: surrogate with the shipped model, "
                   "else physics)"),
               "ste.model");
    add_common_flags(cmd);
    cmd->callback([a] {
      const fs::path map_file = data_dir() / "test-maps" / kDemoMap;
      SteArgs args;
      std::string note;
      if (!a->plume_model.empty()) {
        args.plume_model = a->plume_model;
      } else if (fs::exists(shipped_model())) {
        args.plume_model = "surrogate";
      } else {
        args.plume_model = "physics";
        note = "note: " + shipped_model().string() +
               " is not there yet, so this demo uses the physics plume model "
               "(--plume-model physics); with the trained CNN it uses the surrogate.";
      }
      if (!note.empty() && !output().json) std::cerr << note << "\n";
      const ste::SteOptions options = to_options(args);
      const Map map = read_map(map_file);
      OutputDirectory out(a->out, "demo", {map_file});
      const ste::Scenario sc(map, options);
      const Vec2 source = map.sources.at(kDemoSource);
      const Vec2 start = sc.check_start(kDemoStart);
      const ste::LocalizationResult r = sc.run(source, start, ste::run_seed(1, 0, 0, 0));
      draw_run(sc, source, r, out.open(), args.plume_model);
      out.commit();
      const Pictures p{fs::path(a->out) / "trajectory.png", fs::path(a->out) / "posterior.png"};
      ordered_json j{{"ok", true}, {"map", map_file.string()}, {"plume_model", args.plume_model}};
      if (!note.empty()) j["note"] = note;
      j.update(run_json(sc, source, r));
      j["out"] = {{"trajectory", p.trajectory.string()}, {"posterior", p.posterior.string()}};
      report(j, run_text(sc, source, r) + "\npictures: " + p.trajectory.string() +
                    " (trajectory), " + p.posterior.string() + " (posterior)");
    });
  }
}

}  // namespace plumekit::cli
