// plumekit maps random, plumekit plume, plumekit dataset generate|merge|show:
// random maps, single plumes, and training datasets (dataset/).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>

#include <opencv2/core.hpp>

#include "apps/cli.hpp"
#include "apps/commands.hpp"
#include "cfd/flow_policy.hpp"
#include "core/atomic_file.hpp"
#include "core/map_json.hpp"
#include "core/map_render.hpp"
#include "core/npy.hpp"
#include "core/output_target.hpp"
#include "core/progress.hpp"
#include "dataset/dataset_reader.hpp"
#include "dataset/features.hpp"
#include "dataset/generator.hpp"
#include "dataset/plume.hpp"
#include "dataset/random_maps.hpp"

namespace plumekit::cli {

namespace fs = std::filesystem;
using namespace plumekit::dataset;

namespace {

std::string format_duration(double s) {
  char buf[32];
  const long t = std::lround(std::max(0.0, s));
  std::snprintf(buf, sizeof buf, "%ld:%02ld:%02ld", t / 3600, (t / 60) % 60, t % 60);
  return buf;
}

void add_plume_options(CLI::App* cmd, PlumeOptions& p, std::string& model) {
  cmd->add_option("--model,--plume", model, "Plume model")
      ->capture_default_str()
      ->check(CLI::IsMember({"filament", "advection-diffusion"}));
  bind_field(cmd,
             cmd->add_option("--diffusivity", p.advection_diffusion.diffusivity,
                             "advection-diffusion: eddy diffusivity, m^2/s"),
             "plume.diffusivity")
      ->capture_default_str();
  bind_field(
      cmd,
      cmd->add_option("--release-rate", p.advection_diffusion.release_rate,
                      "Release rate per metre of depth (concentration units * m^2/s), both models"),
      "plume.release_rate")
      ->capture_default_str();
  bind_field(cmd,
             cmd->add_option("--filaments-per-second", p.filament.release_per_second,
                             "filament: filaments released per second"),
             "plume.filaments_per_second")
      ->capture_default_str();
}

void finish_plume_options(PlumeOptions& p, const std::string& model) {
  p.model = parse_plume_model(model);
  p.filament.release_rate = p.advection_diffusion.release_rate;
}

// --families: which random-map families to draw from (default: the thesis's four).
void add_families_option(CLI::App* cmd, RandomMapOptions& o) {
  bind_field(
      cmd,
      cmd->add_option("--families", o.families,
                      "Random-map families, comma-separated: rectangle, two-rectangles, l-shape, "
                      "u-shape (the thesis's, the default), three-rectangles, shape-and-rectangle"),
      "maps.families")
      ->delimiter(',')
      ->default_str("rectangle,two-rectangles,l-shape,u-shape");
}

void add_maps_random(CLI::App& app) {
  auto* group = app.add_subcommand("maps", "Generate maps");
  group->require_subcommand(1);
  auto* cmd = group->add_subcommand("random",
                                    "Random cluttered maps (rectangle, two rectangles, L, U; "
                                    "optionally more), one JSON file each");
  struct Args {
    int count = 10;
    std::uint64_t seed = 0;
    std::string out;
    int sources = 0;
    RandomMapOptions o;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("--count,-n", a->count, "Number of maps")->capture_default_str();
  cmd->add_option("--seed", a->seed, "Seed; map i is the same whatever --count")
      ->capture_default_str();
  cmd->add_option("--out,-o", a->out,
                  "Output folder: new, empty, or an earlier `maps random` output")
      ->required();
  cmd->add_option("--sources", a->sources, "Random sources to store in each map")
      ->capture_default_str();
  bind_field(cmd, cmd->add_option("--width", a->o.width, "Arena width, m"), "maps.width")
      ->capture_default_str();
  bind_field(cmd, cmd->add_option("--height", a->o.height, "Arena height, m"), "maps.height")
      ->capture_default_str();
  bind_field(cmd, cmd->add_option("--min-gap", a->o.min_gap, "Narrowest passage, m"),
             "maps.min_gap")
      ->capture_default_str();
  add_families_option(cmd, a->o);
  bind_field(cmd,
             cmd->add_option("--margin", a->o.robot_margin,
                             "Robot radius + safety that must pass from inlet to outlet, m"),
             "maps.robot_margin")
      ->capture_default_str();
  add_common_flags(cmd);
  cmd->callback([a] {
    if (a->count <= 0) throw InputError("--count must be positive");
    if (a->sources < 0) throw InputError("--sources must not be negative");
    OutputDirectory out(a->out, "maps random");
    std::vector<RandomMap> maps;
    for (int i = 0; i < a->count; ++i) {
      maps.push_back(random_map(a->o, a->seed, i));
      maps.back().map.sources = random_sources(maps.back().map, a->sources, 0.1, a->seed, i);
    }
    const fs::path& dir = out.open();
    std::map<std::string, int> families;
    nlohmann::ordered_json files = nlohmann::ordered_json::array();
    for (int i = 0; i < a->count; ++i) {
      char name[32];
      std::snprintf(name, sizeof name, "map-%05d.json", i);
      maps[i].map.generated_by = "plumekit maps random";
      write_map(maps[i].map, dir / name);
      ++families[maps[i].family];
      files.push_back({{"file", name}, {"family", maps[i].family}});
    }
    out.commit();
    nlohmann::ordered_json j{{"ok", true}, {"out", a->out}, {"seed", a->seed}, {"maps", files}};
    std::ostringstream human;
    human << "wrote " << a->count << " maps to " << a->out << ":";
    for (const auto& [f, n] : families)
      human << " " << n << " " << f;
    report(j, human.str());
  });
}

void add_plume(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "plume", "One source's plume on the 64x64 sensor grid: mean.npy, std.npy, plume.png");
  struct Args {
    std::string map = default_map().string();
    std::string source, out, model = "filament";
    std::uint64_t seed = 0;
    PlumeOptions p;
    cfd::FlowOptions flow;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("MAP", a->map, "Map file (JSON)")->capture_default_str();
  cmd->add_option("--source", a->source, "Source position X,Y in metres")->required();
  cmd->add_option("--out,-o", a->out, "Output folder: new, empty, or an earlier `plume` output")
      ->required();
  cmd->add_option("--seed", a->seed, "Seed of the filament model")->capture_default_str();
  bind_field(cmd, cmd->add_option("--cell", a->flow.cell, "Flow cell size, m"), "flow.cell")
      ->capture_default_str();
  add_plume_options(cmd, a->p, a->model);
  add_common_flags(cmd);
  cmd->callback([a] {
    finish_plume_options(a->p, a->model);
    const Map map = read_map(a->map);
    const Vec2 src = parse_point(a->source, "--source");
    if (!map.is_free(src))
      throw InputError("--source " + to_string(src) +
                       " is outside the arena or inside an obstacle");
    OutputDirectory out(a->out, "plume", {a->map});
    const auto t0 = std::chrono::steady_clock::now();
    const cfd::FlowResult flow = cfd::solve_wind(map, a->flow).flow;  // the flow policy
    const auto t1 = std::chrono::steady_clock::now();
    const GridShape g = feature_grid(map);
    const MapPlumes plumes(map, flow.wind, g, a->p);
    const PlumeTargets t = plumes.run(src, a->seed);
    const auto t2 = std::chrono::steady_clock::now();
    const Picture img = draw_plume(map, t.mean, t.std, src, a->model + " plume", "");
    const fs::path& dir = out.open();
    write_file_atomic(dir / "mean.npy", npy_float32(t.mean.values, {64, 64}));
    write_file_atomic(dir / "std.npy", npy_float32(t.std.values, {64, 64}));
    write_png(img, dir / "plume.png");
    out.commit();
    const double peak = *std::max_element(t.mean.values.begin(), t.mean.values.end());
    const double flow_s = std::chrono::duration<double>(t1 - t0).count();
    const double plume_s = std::chrono::duration<double>(t2 - t1).count();
    nlohmann::ordered_json j{{"ok", true},
                             {"map", a->map},
                             {"source", {src.x, src.y}},
                             {"model", a->model},
                             {"out", a->out},
                             {"peak_mean", peak},
                             {"flow_seconds", flow_s},
                             {"plume_seconds", plume_s}};
    if (a->p.model == PlumeModel::Filament)
      j["filament"] = {{"spinup_seconds", t.filament.spinup_seconds},
                       {"steady", t.filament.steady},
                       {"filaments_at_end", t.filament.filaments_at_end},
                       {"rejected_moves", t.filament.rejected_moves}};
    std::ostringstream human;
    human.precision(3);
    human << "wrote " << a->out << "/{mean,std}.npy, plume.png: " << a->model
          << " plume, peak mean " << peak << "; flow " << flow_s << " s, plume " << plume_s << " s";
    report(j, human.str());
  });
}

void add_generate(CLI::App* group) {
  auto* cmd = group->add_subcommand(
      "generate", "Random maps -> wind -> plumes -> .npy shards + manifest.json (resumable)");
  struct Args {
    DatasetOptions o;
    RunOptions run;
    std::string out, model = "filament", shard, maps_dir;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("--out,-o", a->out, "Dataset directory (created if missing)")->required();
  bind_field(cmd, cmd->add_option("--maps", a->o.maps, "Number of random maps"), "dataset.maps")
      ->capture_default_str();
  bind_field(cmd, cmd->add_option("--sources", a->o.sources, "Sources per map"), "dataset.sources")
      ->capture_default_str();
  cmd->add_option("--seed", a->o.seed, "Seed of everything random")->capture_default_str();
  bind_field(cmd, cmd->add_option("--threads,-j", a->run.threads, "Worker threads (one map each)"),
             "dataset.threads")
      ->capture_default_str();
  bind_field(cmd,
             cmd->add_option("--shard", a->shard,
                             "K/N: do only the maps with index % N == K (then `dataset merge`)"),
             "dataset.shard");
  cmd->add_option("--from-maps", a->maps_dir,
                  "Use the maps in this directory (with their own sources) instead of random "
                  "ones: ground truth for test maps");
  add_families_option(cmd, a->o.map);
  bind_field(cmd, cmd->add_option("--cell", a->o.flow.cell, "Flow cell size, m"), "flow.cell")
      ->capture_default_str();
  add_plume_options(cmd, a->o.plume, a->model);
  add_common_flags(cmd);
  cmd->callback([a] {
    finish_plume_options(a->o.plume, a->model);
    if (!a->shard.empty()) {
      int k = -1, n = 0;
      char slash = 0, extra = 0;
      std::istringstream in(a->shard);
      if (!(in >> k >> slash >> n) || slash != '/' || (in >> extra) || n <= 0 || k < 0 || k >= n)
        throw InputError("--shard: expected K/N with 0 <= K < N, got '" + a->shard + "'");
      a->run.part_k = k;
      a->run.part_n = n;
    }
    if (!a->maps_dir.empty()) {
      if (!fs::is_directory(a->maps_dir))
        throw InputError("--from-maps " + a->maps_dir + ": not a directory");
      std::vector<fs::path> files;
      for (const auto& e : fs::directory_iterator(a->maps_dir))
        if (e.path().extension() == ".json") files.push_back(e.path());
      std::sort(files.begin(), files.end());
      if (files.empty()) throw InputError("--from-maps " + a->maps_dir + ": no .json maps");
      for (const auto& f : files) {
        a->o.given_maps.push_back(read_map(f));
        a->o.map_files.push_back(f.filename().string());
      }
    }
    ProgressBar bar("dataset");
    const auto t0 = std::chrono::steady_clock::now();
    long long first = -1;
    a->run.progress = [&](long long done, long long total) {
      const double el =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      if (first < 0) first = done;  // resumed samples do not count towards the rate
      const double rate = el > 0.0 ? (done - first) / el : 0.0;
      std::ostringstream note;
      note << done << "/" << total << " samples, elapsed " << format_duration(el) << ", ETA "
           << (rate > 0.0 ? format_duration((total - done) / rate) : std::string("--:--:--"));
      bar.update(total > 0 ? static_cast<double>(done) / total : 1.0, note.str());
    };
    const DatasetSummary s = generate_dataset(a->out, a->o, a->run);
    bar.finish();
    nlohmann::ordered_json j{{"ok", true},
                             {"out", a->out},
                             {"model", a->model},
                             {"maps", s.maps},
                             {"maps_resumed", s.maps_resumed},
                             {"winds_cached", s.winds_cached},
                             {"samples_computed", s.samples},
                             {"seconds", s.seconds},
                             {"flow_seconds", s.flow_seconds},
                             {"plume_seconds", s.plume_seconds},
                             {"samples_per_second", s.samples_per_second()},
                             {"threads", a->run.threads}};
    std::ostringstream human;
    human.precision(3);
    human << "wrote " << a->out << ": " << s.maps << " maps (" << s.maps_resumed
          << " already complete), " << s.samples << " samples computed in " << s.seconds << " s ("
          << s.samples_per_second() << " samples/s; flow " << s.flow_seconds << " s, plumes "
          << s.plume_seconds << " s, summed over threads)";
    report(j, human.str());
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
    std::vector<fs::path> parts(a->parts.begin(), a->parts.end());
    const MergeSummary s = merge_datasets(a->out, parts);
    nlohmann::ordered_json j{{"ok", true},
                             {"out", a->out},
                             {"parts", s.parts},
                             {"shards", s.shards},
                             {"samples", s.samples}};
    std::ostringstream human;
    human << "merged " << s.parts << " parts into " << a->out << ": " << s.shards << " shards, "
          << s.samples << " samples, all checksums verified";
    report(j, human.str());
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
  cmd->add_option("--index,-i", a->index, "Sample index over the whole dataset")
      ->capture_default_str();
  cmd->add_option("--out,-o", a->out, "PNG file (new, or a picture plumekit drew)")->required();
  add_common_flags(cmd);
  cmd->callback([a] {
    const fs::path dir = a->dir;
    check_output_file(a->out, {dir});
    // The one validating reader: the manifest, then the drawn shard against its checksums.
    const Manifest m = read_manifest(dir / "manifest.json");
    long long start = 0;
    for (const ManifestShard& s : m.shards) {
      const long long n = s.samples;
      if (a->index < start || a->index >= start + n) {
        start += n;
        continue;
      }
      const int k = static_cast<int>(a->index - start);
      const ShardArrays arrays = read_shard(dir, s);
      const Map map = read_map(dir / s.map);
      const GridShape g = feature_grid(map);
      if (g.size() != static_cast<std::size_t>(arrays.nx) * arrays.ny)
        throw InputError((dir / s.map).string() + ": its feature grid is not the shard's");
      auto channel = [&](const std::vector<float>& arr, int channels, int c) {
        Grid<double> f(g, 0.0);
        const std::size_t off = (static_cast<std::size_t>(k) * channels + c) * g.size();
        std::copy(arr.begin() + off, arr.begin() + off + g.size(), f.values.begin());
        return f;
      };
      const Vec2 source{arrays.sources[2 * k], arrays.sources[2 * k + 1]};
      const std::vector<float>&in = arrays.inputs, &tg = arrays.targets;
      write_png(
          draw_field_panels(
              map,
              {{channel(in, 3, 0), "input 0: region label", "region label [-]"},
               {channel(in, 3, 1), "input 1: signed distance to surfaces", "distance [m]"},
               {channel(in, 3, 2), "input 2: distance to the source", "distance [m]"},
               {channel(tg, 2, 0), "target 0: mean concentration", "mean [conc. units]", true},
               {channel(tg, 2, 1), "target 1: std of concentration", "std [conc. units]", true}},
              source),
          a->out);
      nlohmann::ordered_json j{{"ok", true},        {"out", a->out},
                               {"index", a->index}, {"shard", s.name},
                               {"map", s.map},      {"source", {source.x, source.y}}};
      std::ostringstream human;
      human << "wrote " << a->out << ": sample " << a->index << " (" << s.name << ", source "
            << to_string(source) << ")";
      report(j, human.str());
      return;
    }
    throw InputError("--index " + std::to_string(a->index) + ": the dataset has " +
                     std::to_string(start) + " samples");
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
