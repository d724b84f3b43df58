// plumekit maps random, plumekit plume, plumekit dataset generate|merge|show:
// random maps, single plumes, and training datasets (dataset/).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <map>
#include <optional>
#include <sstream>

#include <opencv2/core.hpp>

#include "apps/cli.hpp"
#include "apps/commands.hpp"
#include "cfd/flow_policy.hpp"
#include "cfd/wind_file.hpp"
#include "core/animation.hpp"
#include "core/atomic_file.hpp"
#include "core/npy.hpp"
#include "core/output_target.hpp"
#include "core/progress.hpp"
#include "core/vti.hpp"
#include "dataset/dataset_reader.hpp"
#include "dataset/generator.hpp"
#include "dataset/map_set.hpp"
#include "dataset/option_tables.hpp"
#include "dataset/plume.hpp"
#include "dataset/random_maps.hpp"
#include "dataset/reports.hpp"
#include "map/map_json.hpp"
#include "map/map_render.hpp"
#include "run/replay_render.hpp"
#include "surrogate/features.hpp"
#include "world/option_tables.hpp"

namespace plumekit::cli {

namespace fs = std::filesystem;
using namespace plumekit::dataset;

namespace {

// --simulator, the simulation that makes the plume (old spellings --plume-model, --model and
// --plume kept as deprecated aliases: `localize`'s --plume-model is the estimator's model, a
// different thing), and the plume options, bound to the library's fields.
void add_plume_options(CLI::App* cmd, PlumeOptions& p) {
  // A kind's name becomes the enum's number for CLI11; the library parses the name and words
  // the error.
  const CLI::Validator names(
      [](std::string& kind) {
        try {
          kind = std::to_string(static_cast<int>(parse_plume_simulator(kind)));
          return std::string();
        } catch (const OptionError& e) {
          return e.message();
        }
      },
      "", "plume model kind");
  bind_field(cmd,
             cmd->add_option("--simulator", p.model,
                             "What simulates the plume: filament (the world's filaments), "
                             "advection-diffusion (their steady mean)")
                 ->transform(names)
                 ->type_name("KIND")
                 ->default_str(to_string(p.model)),
             "plume.model");
  for (const char* old : {"--plume-model", "--model", "--plume"})
    add_deprecated_alias(cmd, old, "--simulator", p.model)->transform(names);
  add_table_flags(cmd, p.advection_diffusion, cfd::advection_diffusion_option_table(),
                  {"plume.diffusivity"});
  bind_field(cmd,
             cmd->add_option_function<double>(
                    "--release-rate", [&p](double rate) { p.set_release_rate(rate); },
                    "Release rate per metre of depth (concentration units * m^2/s), both models")
                 ->default_str(CLI::detail::to_string(p.advection_diffusion.release_rate)),
             "plume.release_rate");
  add_table_flags(cmd, p.filament, world::filament_option_table(), {"plume.filaments_per_second"});
  add_world_options(cmd, p.filament);
  add_gas_sensor_options(cmd, p.sensor, "The static sensors'");
}

// --families: which random-map families to draw from (default: the thesis's four).
void add_families_option(CLI::App* cmd, RandomMapOptions& o) {
  bind_field(
      cmd,
      cmd->add_option("--families", o.families,
                      "Random-map families, comma-separated: rectangle, two-rectangles, l-shape, "
                      "u-shape (the thesis's, the default), three-rectangles, shape-and-rectangle, "
                      "building (floor plans)"),
      "maps.families")
      ->delimiter(',')
      ->default_str(CLI::detail::join(o.families, ","));
}

void add_maps_random(CLI::App& app) {
  auto* group = app.add_subcommand("maps", "Generate maps");
  group->require_subcommand(1);
  auto* cmd = group->add_subcommand("random",
                                    "Random cluttered maps (rectangle, two rectangles, L, U; "
                                    "optionally more), one JSON file each");
  struct Args {
    std::string out;
    MapSetOptions o;
  };
  auto a = std::make_shared<Args>();
  add_table_flags(cmd, a->o, map_set_option_table(), {"maps.count"});
  add_seed_flag(cmd, a->o.seed, "Seed; map i is the same whatever --count");
  cmd->add_option("--out,-o", a->out,
                  "Output folder: new, empty, or an earlier `maps random` output")
      ->required();
  add_table_flags(cmd, a->o, map_set_option_table(), {"maps.sources"});
  RandomMapOptions& m = a->o.map;
  add_table_flags(cmd, m, random_map_option_table(), {"maps.width", "maps.height", "maps.min_gap"});
  add_families_option(cmd, m);
  add_table_flags(cmd, m, random_map_option_table(),
                  {"maps.building_min_size", "maps.building_max_size", "maps.building_passage",
                   "maps.robot_margin"});
  add_common_flags(cmd);
  cmd->callback([a] {
    OutputDirectory out(a->out, "maps random");
    std::vector<RandomMap> maps = random_map_set(a->o);
    const Report r = write_map_set(out.open(), a->out, a->o, maps);
    out.commit();
    report(r.json, r.text);
  });
}

// The plume over time as a ParaView time series: DIR/plume.pvd over DIR/series/plume-NNNN.vti
// (the concentration per cell, the map frame's coordinates), a frame a second.
void write_series(const fs::path& dir, const Map& map, const SinglePlume::Series& series) {
  fs::create_directories(dir / "series");
  std::ostringstream pvd;
  pvd << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      << "  <Collection>\n";
  for (std::size_t k = 0; k < series.frames.size(); ++k) {
    char name[32];
    std::snprintf(name, sizeof name, "plume-%04zu.vti", k);
    write_file_atomic(dir / "series" / name,
                      vti_cell_data(series.grid, {{"concentration", 1, series.frames[k]}}, "",
                                    "concentration", map.to_frame({0.0, 0.0})));
    pvd << "    <DataSet timestep=\"" << static_cast<double>(k) * series.every_s
        << "\" group=\"\" part=\"0\" file=\"series/" << name << "\"/>\n";
  }
  pvd << "  </Collection>\n</VTKFile>\n";
  write_file_atomic(dir / "plume.pvd", pvd.str());
}

void add_plume(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "plume", "One source's plume on the 64x64 sensor grid: mean.npy, std.npy, plume.png");
  struct Args {
    std::string map, source, out, wind, animate;
    std::uint64_t seed = kDefaultSeed;
    PlumeOptions p;
    cfd::FlowOptions flow;
    double seconds = 60.0;
    bool series = false;
  };
  auto a = std::make_shared<Args>();
  add_map_argument(cmd, a->map);
  bind_field(cmd, cmd->add_option("--source", a->source, "Source position X,Y in metres"),
             "plume.source")
      ->required();
  cmd->add_option("--out,-o", a->out, "Output folder: new, empty, or an earlier `plume` output")
      ->required();
  add_seed_flag(cmd, a->seed, "Seed of the filament model");
  add_table_flags(cmd, a->flow, cfd::flow_option_table(), {"flow.cell"});
  cmd->add_option("--wind", a->wind, cfd::kWindHelp)->check(CLI::ExistingDirectory);
  add_plume_options(cmd, a->p);
  cmd->add_option("--animate", a->animate,
                  "Also write the filament plume as it moves, a frame a second after the spin-up: "
                  "FILE.mp4 (a video) or FILE.png (an animated PNG; docs/replay.md)")
      ->type_name("FILE");
  cmd->add_option("--seconds", a->seconds, "How long --animate and --series follow the plume, s")
      ->capture_default_str()
      ->check(CLI::Range(1.0, 3600.0));
  cmd->add_flag("--series", a->series,
                "Also write the plume over time as a ParaView time series: plume.pvd over "
                "series/plume-NNNN.vti, a frame a second");
  add_common_flags(cmd);
  cmd->callback([a] {
    const Map map = read_map(a->map);
    const Vec2 src =
        map.from_frame(parse_point(a->source, "--source"));  // typed in the map's frame
    check_source(map, src);                                  // before the output folder is checked
    const bool over_time = a->series || !a->animate.empty();
    if (over_time && a->p.model != PlumeSimulator::Filament)
      throw InputError(
          "--animate and --series follow the filament plume; the advection-diffusion "
          "plume is steady (--simulator filament)");
    if (!a->animate.empty()) check_animation_target(a->animate, "--animate");
    OutputDirectory out(a->out, "plume", {a->map, a->wind});
    a->p.filament.threads = 0;  // one plume: every core (it does not depend on the count)
    const SinglePlume plume =
        single_plume(map, src, a->p, a->flow, a->seed, a->wind, over_time ? a->seconds : 0.0);
    const PlumeTargets& t = plume.targets;
    const Picture img =
        draw_plume(map, t.mean, t.std, src, std::string(to_string(a->p.model)) + " plume", "");
    const fs::path& dir = out.open();
    write_file_atomic(dir / "mean.npy", npy_float32(t.mean.values, {64, 64}));
    write_file_atomic(dir / "std.npy", npy_float32(t.std.values, {64, 64}));
    write_png(img, dir / "plume.png");
    if (a->series) write_series(dir, map, plume.series);
    std::optional<AnimationWriter::Written> video;
    if (!a->animate.empty()) {
      const Vec2 s = map.to_frame(src);
      std::ostringstream title;
      title << std::fixed << std::setprecision(2) << (map.name.empty() ? "map" : map.name)
            << ": filament plume of (" << s.x << ", " << s.y << "), seed " << a->seed;
      run::AnimateOptions o;
      o.progress = !output().json;
      video = run::animate_plume(map, src, plume.series.grid, plume.series.frames,
                                 plume.series.every_s, title.str(), a->animate, "--animate", o);
    }
    out.commit();
    const PlumeRun run{a->map, a->out, map.to_frame(src), a->p.model, plume.flow_s, plume.plume_s};
    Report r = plume_report(run, t);
    if (a->series) {
      r.json["series"] = (fs::path(a->out) / "plume.pvd").string();
      r.text += "\nwrote " + (fs::path(a->out) / "plume.pvd").string() + " (" +
                std::to_string(plume.series.frames.size()) + " frames in series/)";
    }
    if (video) run::report_animation(*video, r.json, r.text);
    report(r.json, r.text);
  });
}

void add_generate(CLI::App* group) {
  auto* cmd = group->add_subcommand(
      "generate", "Random maps -> wind -> plumes -> .npy shards + manifest.json (resumable)");
  struct Args {
    DatasetOptions o;
    RunOptions run;
    std::string out, map_dir;
    std::vector<double> inlet_speeds;  // LO,HI (dataset.inlet_speeds)
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("--out,-o", a->out, "Dataset directory (created if missing)")->required();
  add_table_flags(cmd, a->o, dataset_option_table(), {"dataset.maps", "dataset.sources"});
  add_seed_flag(cmd, a->o.seed, "Seed of everything random");
  add_threads_flag(cmd, a->run.threads, "dataset.threads",
                   "Worker threads, one map each (0: one per core)");
  bind_field(cmd,
             cmd->add_option_function<std::string>(
                 "--shard", [a](const std::string& k_of_n) { a->run.set_part(k_of_n); },
                 "K/N: do only the maps with index % N == K (then `dataset merge`)"),
             "dataset.shard");
  bind_field(cmd,
             cmd->add_option("--map-dir", a->map_dir,
                             "Use the maps in this directory (with their own sources) instead of "
                             "random ones: ground truth for test maps"),
             "dataset.map_dir");
  add_deprecated_alias(cmd, "--from-maps", "--map-dir", a->map_dir);
  add_families_option(cmd, a->o.map);
  add_table_flags(cmd, a->o.flow, cfd::flow_option_table(), {"flow.cell"});
  add_table_flags(cmd, a->o, dataset_option_table(),
                  {"dataset.feature_cell", "dataset.physics_input"});
  bind_field(cmd,
             cmd->add_option("--inlet-speeds", a->inlet_speeds,
                             "LO,HI: each random map's inlets blow at a speed drawn uniformly "
                             "from LO..HI m/s (default: 1 m/s)")
                 ->delimiter(',')
                 ->expected(2),
             "dataset.inlet_speeds");
  add_plume_options(cmd, a->o.plume);
  add_common_flags(cmd);
  cmd->callback([a] {
    if (!a->map_dir.empty()) use_map_dir(a->o, a->map_dir);
    if (a->inlet_speeds.size() == 2) {
      a->o.inlet_speed_lo = a->inlet_speeds[0];
      a->o.inlet_speed_hi = a->inlet_speeds[1];
    }
    ProgressBar bar("dataset");
    ProgressNote note;
    a->run.progress = [&](long long done, long long total) {
      bar.update(total > 0 ? static_cast<double>(done) / total : 1.0, note(done, total));
    };
    const DatasetSummary s = generate_dataset(a->out, a->o, a->run);
    bar.finish();
    const Report r = generate_report(a->out, a->o.plume.model, s);
    report(r.json, r.text);
  });
}

void add_merge(CLI::App* group) {
  auto* cmd = group->add_subcommand(
      "merge", "Join the parts of a --shard K/N run into one dataset, verifying checksums");
  struct Args {
    std::string out;
    std::vector<std::string> parts;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("PARTS", a->parts, "Part directories (the same one may hold several parts)")
      ->required();
  cmd->add_option("--out,-o", a->out, "Merged dataset directory (may be a part's)")->required();
  add_common_flags(cmd);
  cmd->callback([a] {
    const Report r =
        merge_report(a->out, merge_datasets(a->out, {a->parts.begin(), a->parts.end()}));
    report(r.json, r.text);
  });
}

void add_show(CLI::App* group) {
  auto* cmd = group->add_subcommand(
      "show", "Draw one sample: its three features, the mean and the std, with the obstacles");
  struct Args {
    std::string dir, out;
    long long index = 0;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("DIR", a->dir, "Dataset directory")->required();
  bind_field(cmd, cmd->add_option("--index,-i", a->index, "Sample index over the whole dataset"),
             "show.index")
      ->capture_default_str();
  cmd->add_option("--out,-o", a->out, "PNG file (new, or a picture plumekit drew)")->required();
  add_common_flags(cmd);
  cmd->callback([a] {
    check_output_file(a->out, {a->dir});
    // The one validating reader: the manifest, then the drawn shard against its checksums.
    const DatasetSample s = read_sample(a->dir, a->index);
    const Map& map = s.map;
    // Thesis datasets have 3 input channels; physical-grid ones (--feature-cell) 5, with the wind,
    // and 6 with the physics plume (--physics-input).
    const bool wind = s.inputs.size() >= 5;
    std::vector<FieldPanel> panels = {
        {s.inputs[0], "input 0: region label", "region label [-]"},
        {s.inputs[1], "input 1: signed distance to surfaces", "distance [m]"}};
    if (wind) {
      panels.push_back({s.inputs[2], "input 2: wind u", "u [m/s]"});
      panels.push_back({s.inputs[3], "input 3: wind v", "v [m/s]"});
    }
    if (s.inputs.size() == 6)
      panels.push_back({s.inputs[4], "input 4: physics plume (advection-diffusion mean)",
                        "mean [concentration units]", true});
    panels.push_back({s.inputs.back(),
                      "input " + std::to_string(s.inputs.size() - 1) + ": distance to the source",
                      "distance [m]"});
    panels.push_back(
        {s.targets[0], "target 0: mean concentration", "mean [concentration units]", true});
    panels.push_back(
        {s.targets[1], "target 1: std of concentration", "std [concentration units]", true});
    write_png(draw_field_panels(map, panels, s.source), a->out);
    const Report r = show_report(a->out, s);
    report(r.json, r.text);
  });
}

}  // namespace

void add_dataset_commands(CLI::App& app) {
  add_maps_random(app);
  add_plume(app);
  auto* group = app.add_subcommand("dataset", "Training datasets: generate, merge, show");
  group->require_subcommand(1);
  add_generate(group);
  add_merge(group);
  add_show(group);
}

}  // namespace plumekit::cli
