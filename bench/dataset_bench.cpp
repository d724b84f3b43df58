// Dataset generation speed: samples per second of each plume model with the
// flow solves included, on a slice of the thesis-scale dataset (the first
// --maps maps of seed 1, 100 sources each), extrapolated to 180 x 100.
//
//   ./build/bench/dataset_bench [--maps 10] [--threads 2] [--repeats 1] [--out DIR]
//                               [--occlusion] [--unsteady] [--engines [--buildings]]
//
// By default it compares the two plume models; with --occlusion and/or
// --unsteady it compares the filament model with line of sight and/or the
// unsteady wind (issue 18) against the thesis-style one; the thesis-scale
// target is 15 min, 1.44x the 10 min 25 s measured without them.
// With --engines it compares the default (faithful) world's two engines (issue 45): the fast
// one against V1, the world before it (targets: the thesis scale within 5 min, and with
// --buildings, the v2 surrogate's random buildings, 16 sources each on a 0.1 m flow grid and
// 0.2 m cells, extrapolated to 1,000 plumes, within 10 min).
//
// Extrapolation is linear in the number of maps: maps are independent, each
// costs one flow solve plus 100 plume samples, and the slice draws its maps
// from the same distribution as the full dataset. With --repeats N the two
// models run alternately N times, so that both see the same machine state,
// and the table gives medians (the ratio is the median of the N ratios).
#include <sys/resource.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "core/statistics.hpp"
#include "dataset/generator.hpp"

using namespace plumekit::dataset;
using plumekit::median;
namespace fs = std::filesystem;

namespace {

struct Run {
  double rate = 0.0;          // samples per second, flow included
  double flow_per_map = 0.0;  // thread-seconds
  double plume = 0.0;         // thread-seconds per sample
  double wall = 0.0;
};

struct Setting {
  const char* label;
  PlumeSimulator model;
  bool occlusion;
  bool unsteady;
  plumekit::world::PlumeEngine engine = plumekit::world::PlumeEngine::Fast;
};

// The slice: the thesis-scale dataset's first maps, or (buildings) the v2 surrogate's random
// buildings as scripts/train-model-v2.sh draws them.
struct Slice {
  bool buildings = false;
  int sources() const { return buildings ? 16 : 100; }
  int full_samples() const { return buildings ? 1000 : 180 * 100; }
  const char* full_name() const { return buildings ? "1,000 buildings' plumes" : "thesis scale"; }
};

Run run_setting(const Setting& setting, const Slice& slice, int maps, int threads,
                const fs::path& out) {
  DatasetOptions o;
  o.maps = maps;
  o.sources = slice.sources();
  o.seed = 1;
  if (slice.buildings) {
    o.seed = 22;
    o.map.families = {"building"};
    o.flow.cell = 0.1;
    o.feature_cell = 0.2;
    o.inlet_speed_lo = 0.3;
    o.inlet_speed_hi = 2.0;
  }
  o.plume.model = setting.model;
  o.plume.filament.occlusion = setting.occlusion;
  o.plume.filament.unsteady_wind = setting.unsteady;
  o.plume.filament.engine = setting.engine;
  RunOptions run;
  run.threads = threads;
  const fs::path dir = out / setting.label;
  fs::remove_all(dir);  // time a cold run: every flow solved
  const DatasetSummary s = generate_dataset(dir, o, run);
  fs::remove_all(dir);
  return {s.samples_per_second(), s.flow_s / s.maps, s.plume_s / s.samples, s.seconds};
}

}  // namespace

int main(int argc, char** argv) {
  int maps = 10, threads = 2, repeats = 1;
  bool occlusion = false, unsteady = false, engines = false;
  Slice slice;
  fs::path out = fs::temp_directory_path() / "plumekit-dataset-bench";
  // Flags in any order; --maps, --threads, --repeats and --out take a value.
  for (int k = 1; k < argc; ++k) {
    const bool valued = k + 1 < argc;
    if (!std::strcmp(argv[k], "--maps") && valued)
      maps = std::atoi(argv[++k]);
    else if (!std::strcmp(argv[k], "--threads") && valued)
      threads = std::atoi(argv[++k]);
    else if (!std::strcmp(argv[k], "--repeats") && valued)
      repeats = std::max(1, std::atoi(argv[++k]));
    else if (!std::strcmp(argv[k], "--out") && valued)
      out = argv[++k];
    else if (!std::strcmp(argv[k], "--occlusion"))
      occlusion = true;
    else if (!std::strcmp(argv[k], "--unsteady"))
      unsteady = true;
    else if (!std::strcmp(argv[k], "--engines"))
      engines = true;
    else if (!std::strcmp(argv[k], "--buildings"))
      slice.buildings = true;
    else {
      std::fprintf(stderr, "dataset_bench: unknown argument %s (see the comment at the top)\n",
                   argv[k]);
      return 2;
    }
  }
  if (engines) occlusion = unsteady = false;  // the engines' comparison is in the default world
  const int full_samples = slice.full_samples();
  std::printf("slice: %d %s x %d sources, %d threads, %d repeat(s); %s: %d plumes\n", maps,
              slice.buildings ? "buildings" : "maps", slice.sources(), threads, repeats,
              slice.full_name(), full_samples);
  const bool faithful = occlusion || unsteady;
  const char* faithful_label = occlusion && unsteady ? "filament-occl-unsteady"
                               : occlusion           ? "filament-occlusion"
                                                     : "filament-unsteady";
  using plumekit::world::PlumeEngine;
  const Setting settings[2] = {
      engines ? Setting{"faithful-v1", PlumeSimulator::Filament, true, true, PlumeEngine::V1}
              : Setting{"filament", PlumeSimulator::Filament, false, false},
      engines ? Setting{"faithful (fast)", PlumeSimulator::Filament, true, true}
      : faithful
          ? Setting{faithful_label, PlumeSimulator::Filament, occlusion, unsteady}
          : Setting{"advection-diffusion", PlumeSimulator::AdvectionDiffusion, false, false}};
  std::vector<Run> runs[2];
  std::vector<double> ratios, plume_ratios;
  for (int r = 0; r < repeats; ++r) {
    for (int m = 0; m < 2; ++m) {
      runs[m].push_back(run_setting(settings[m], slice, maps, threads, out));
      const Run& x = runs[m].back();
      if (repeats > 1)
        std::printf("  repeat %d %-20s %7.1f samples/s | flow %.2f s/map | plume %.2f ms/sample\n",
                    r + 1, settings[m].label, x.rate, x.flow_per_map, 1e3 * x.plume);
    }
    ratios.push_back(runs[1].back().rate / runs[0].back().rate);
    plume_ratios.push_back(runs[0].back().plume / runs[1].back().plume);
  }
  for (int m = 0; m < 2; ++m) {
    std::vector<double> rate, flow, plume, wall;
    for (const Run& x : runs[m]) {
      rate.push_back(x.rate);
      flow.push_back(x.flow_per_map);
      plume.push_back(x.plume);
      wall.push_back(x.wall);
    }
    std::printf(
        "%-20s %7.1f samples/s (flow included) | flow %.2f s/map | plume %.2f ms/sample "
        "(thread time) | wall %.1f s | %s ~%.1f min\n",
        settings[m].label, median(rate), median(flow), 1e3 * median(plume), median(wall),
        slice.full_name(), full_samples / median(rate) / 60.0);
  }
  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  const char* of_repeats = repeats > 1 ? " (medians of the repeats' ratios)" : "";
  if (engines)
    std::printf("fast vs v1: %.2fx samples/s with the flow, %.2fx per plume%s\n", median(ratios),
                median(plume_ratios), of_repeats);
  else if (faithful)
    std::printf(
        "%s vs filament: %.2fx the time with the flow, %.2fx per plume%s; "
        "thesis scale ~%.1f min at 10 min 25 s without\n",
        faithful_label, 1.0 / median(ratios), 1.0 / median(plume_ratios), of_repeats,
        624.8 / median(ratios) / 60.0);
  else
    std::printf(
        "advection-diffusion vs filament: %.1fx samples/s with the flow, %.1fx per plume%s\n",
        median(ratios), median(plume_ratios), of_repeats);
  std::printf(
      "peak resident memory: %.0f MB (independent of the number of maps: one map per "
      "thread in memory)\n",
      ru.ru_maxrss / 1024.0);
  return 0;
}
