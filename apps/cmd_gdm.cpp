// plumekit gdm: gas distribution maps (Kernel DM+V, DM+V/W) from a robot's readings.
#include <filesystem>

#include "apps/cli.hpp"
#include "apps/commands.hpp"
#include "cfd/flow_policy.hpp"
#include "cfd/wind_file.hpp"
#include "core/atomic_file.hpp"
#include "core/npy.hpp"
#include "core/option_check.hpp"
#include "core/output_target.hpp"
#include "core/progress.hpp"
#include "core/thread_pool.hpp"
#include "map/map_json.hpp"
#include "methods/kernel_dmv.hpp"
#include "methods/option_tables.hpp"
#include "run/gdm_render.hpp"
#include "run/gdm_report.hpp"
#include "run/gdm_samples.hpp"
#include "run/gdm_score.hpp"

namespace plumekit::cli {

namespace {

namespace fs = std::filesystem;

struct GdmArgs {
  std::string map, samples, run, out, source, wind;
  bool map_given = false;  // MAP typed: it replaces the map a --run recorded
  int threads = kDefaultThreads;
  methods::GdmOptions options;
  cfd::FlowOptions flow;
};

void bind_gdm_options(CLI::App* cmd, GdmArgs& a) {
  add_table_flags(cmd, a.options, methods::gdm_option_table());
}

// The map and samples to work on: the CSV's on MAP, or a run's on the map it recorded (MAP when
// typed) with every robot's samples.
struct Inputs {
  std::string map_file;
  Map map;
  std::vector<methods::Sample> samples;
};

Inputs read_inputs(const GdmArgs& a) {
  Inputs in;
  if (!a.samples.empty()) {
    in.map_file = a.map;
    in.map = read_map(a.map);
    in.samples = run::read_samples_csv(a.samples, in.map);
    return in;
  }
  const fs::path run = fs::is_directory(a.run) ? fs::path(a.run) / "run.json" : fs::path(a.run);
  const nlohmann::json j = run::parse_run_json(read_file(run), run.string());
  in.map_file =
      a.map_given
          ? a.map
          : run::find_run_map(
                j, run, {data_dir() / "maps", data_dir() / "test-maps", data_dir() / "floors"})
                .string();
  in.map = read_map(in.map_file);
  in.samples = run::run_samples(j, run.string(), in.map);
  return in;
}

// The maps, on --threads, with a progress bar (on a terminal) for long work.
methods::GdmMaps make_maps(const Inputs& in, const GdmArgs& a) {
  ThreadPool pool(a.threads);
  ProgressBar bar("gdm");
  methods::GdmWork work{&pool, [&](double done) { bar.update(done); }};
  methods::GdmMaps maps = methods::kernel_dmv(in.map, in.samples, a.options, work);
  bar.finish();
  return maps;
}

void write_maps(const fs::path& dir, const methods::GdmMaps& maps) {
  const GridShape& g = maps.mean.shape;
  const std::vector<std::size_t> shape{static_cast<std::size_t>(g.ny),
                                       static_cast<std::size_t>(g.nx)};
  write_file_atomic(dir / "mean.npy", npy_float64(maps.mean.values, shape));
  write_file_atomic(dir / "variance.npy", npy_float64(maps.variance.values, shape));
  write_file_atomic(dir / "confidence.npy", npy_float64(maps.confidence.values, shape));
}

}  // namespace

void add_gdm_commands(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "gdm",
      "Gas distribution maps (Kernel DM+V, DM+V/W) from readings: mean, variance and confidence "
      ".npy and gdm.png; scored against the true mean plume with --source");
  auto a = std::make_shared<GdmArgs>();
  add_map_argument(cmd, a->map);
  auto* csv =
      cmd->add_option("--samples", a->samples,
                      "CSV of readings: a header naming x, y, reading (and u, v), map frame");
  auto* run = cmd->add_option(
      "--run", a->run,
      "A `plumekit localize --out` folder (or its run.json): every robot's samples, "
      "on the map the run recorded (MAP, when given, replaces it)");
  csv->excludes(run);
  cmd->add_option("--source", a->source, "The true source X,Y: score the maps against its plume");
  cmd->add_option("--wind", a->wind, cfd::kWindHelp)->check(CLI::ExistingDirectory);
  add_table_flags(cmd, a->flow, cfd::flow_option_table(), {"flow.cell"});
  cmd->add_option("--out,-o", a->out, "Output folder: new, empty, or an earlier `gdm` output")
      ->required();
  bind_gdm_options(cmd, *a);
  add_threads_flag(cmd, a->threads, "gdm.threads",
                   "Threads of the kernel sums (0: one per core; the maps are the same bytes for "
                   "any count)");
  add_common_flags(cmd);
  cmd->callback([a, cmd] {
    if (a->samples.empty() && a->run.empty())
      throw OptionError("gdm.samples", "give --samples CSV or --run DIR");
    a->options.validate();
    check_count("gdm.threads", a->threads, 0, 1024, "0 means one per core");
    a->map_given = cmd->get_option("MAP")->count() > 0;
    const Inputs in = read_inputs(*a);
    run::GdmRun r{in.map_file, a->samples.empty() ? a->run : a->samples, a->out, a->options, {},
                  {}};
    if (!a->source.empty()) r.source = in.map.from_frame(parse_point(a->source, "--source"));
    methods::check_grid_memory(
        in.map, a->options.cell,
        methods::kGdmBytesPerCell + (r.source ? run::kScoreBytesPerCell : 0.0));
    OutputDirectory out(a->out, "gdm", {in.map_file, a->samples, a->run, a->wind});
    const methods::GdmMaps maps = make_maps(in, *a);
    if (r.source) {
      const cfd::WindField wind = a->wind.empty() ? cfd::solve_wind(in.map, a->flow).flow.wind
                                                  : cfd::read_wind(a->wind, in.map);
      r.score = run::score_mean(maps.mean,
                                run::true_mean_plume(in.map, wind, *r.source, maps.mean.shape));
    }
    const fs::path& dir = out.open();
    write_maps(dir, maps);
    write_png(run::draw_gdm(in.map, maps, in.samples, r.source,
                            run::method_name(a->options, in.samples), ""),
              dir / "gdm.png");
    const Report rep = run::gdm_report(in.map, maps, r);
    write_file_atomic(dir / "gdm.json", rep.json.dump(2) + "\n");
    out.commit();
    report(rep.json, rep.text + "\nwrote " + a->out +
                         "/{mean,variance,confidence}.npy (float64, NaN in obstacles), gdm.png, "
                         "gdm.json");
  });
}

}  // namespace plumekit::cli
