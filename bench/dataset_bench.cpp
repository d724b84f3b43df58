// Dataset generation speed: samples per second of each plume model with the
// flow solves included, on a slice of the thesis-scale dataset (the first
// --maps maps of seed 1, 100 sources each), extrapolated to 180 x 100.
//
//   ./build/bench/dataset_bench [--maps 10] [--threads 2] [--repeats 1] [--out DIR]
//                               [--occlusion] [--unsteady]
//
// By default it compares the two plume models; with --occlusion and/or
// --unsteady it compares the filament model with line of sight and/or the
// unsteady wind (issue 18) against the thesis-style one; the thesis-scale
// target is 15 min, 1.44x the 10 min 25 s measured without them.
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
};

Run run_setting(const Setting& setting, int maps, int threads, const fs::path& out) {
  DatasetOptions o;
  o.maps = maps;
  o.sources = 100;
  o.seed = 1;
  o.plume.model = setting.model;
  o.plume.filament.occlusion = setting.occlusion;
  o.plume.filament.unsteady_wind = setting.unsteady;
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
  bool occlusion = false, unsteady = false;
  fs::path out = fs::temp_directory_path() / "plumekit-dataset-bench";
  for (int k = 1; k + 1 < argc; k += 2) {
    if (!std::strcmp(argv[k], "--maps")) maps = std::atoi(argv[k + 1]);
    if (!std::strcmp(argv[k], "--threads")) threads = std::atoi(argv[k + 1]);
    if (!std::strcmp(argv[k], "--repeats")) repeats = std::max(1, std::atoi(argv[k + 1]));
    if (!std::strcmp(argv[k], "--out")) out = argv[k + 1];
  }
  for (int k = 1; k < argc; ++k) {
    if (!std::strcmp(argv[k], "--occlusion")) occlusion = true;
    if (!std::strcmp(argv[k], "--unsteady")) unsteady = true;
  }
  const int thesis_samples = 180 * 100;
  std::printf(
      "slice: %d maps x 100 sources, seed 1, %d threads, %d repeat(s); thesis scale: 180 x 100\n",
      maps, threads, repeats);
  const bool faithful = occlusion || unsteady;
  const char* faithful_label = occlusion && unsteady ? "filament-occl-unsteady"
                               : occlusion           ? "filament-occlusion"
                                                     : "filament-unsteady";
  const Setting settings[2] = {
      {"filament", PlumeSimulator::Filament, false, false},
      faithful ? Setting{faithful_label, PlumeSimulator::Filament, occlusion, unsteady}
               : Setting{"advection-diffusion", PlumeSimulator::AdvectionDiffusion, false, false}};
  std::vector<Run> runs[2];
  std::vector<double> ratios, plume_ratios;
  for (int r = 0; r < repeats; ++r) {
    for (int m = 0; m < 2; ++m) {
      runs[m].push_back(run_setting(settings[m], maps, threads, out));
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
        "(thread time) | wall %.1f s | thesis scale ~%.1f min\n",
        settings[m].label, median(rate), median(flow), 1e3 * median(plume), median(wall),
        thesis_samples / median(rate) / 60.0);
  }
  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  const char* of_repeats = repeats > 1 ? " (medians of the repeats' ratios)" : "";
  if (faithful)
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
