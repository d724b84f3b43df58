// Dataset generation speed: samples per second of each plume model with the
// flow solves included, on a slice of the thesis-scale dataset (the first
// --maps maps of seed 1, 100 sources each), extrapolated to 180 x 100.
//
//   ./build/bench/dataset_bench [--maps 10] [--threads 2] [--out DIR]
//
// Extrapolation is linear in the number of maps: maps are independent, each
// costs one flow solve plus 100 plume samples, and the slice draws its maps
// from the same distribution as the full dataset.
#include <sys/resource.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>

#include "dataset/generator.hpp"

using namespace plumekit::dataset;
namespace fs = std::filesystem;

int main(int argc, char** argv) {
  int maps = 10, threads = 2;
  fs::path out = fs::temp_directory_path() / "plumekit-dataset-bench";
  for (int k = 1; k + 1 < argc; k += 2) {
    if (!std::strcmp(argv[k], "--maps")) maps = std::atoi(argv[k + 1]);
    if (!std::strcmp(argv[k], "--threads")) threads = std::atoi(argv[k + 1]);
    if (!std::strcmp(argv[k], "--out")) out = argv[k + 1];
  }
  const int thesis_samples = 180 * 100;
  std::printf("slice: %d maps x 100 sources, seed 1, %d threads; thesis scale: 180 x 100\n", maps,
              threads);
  double filament_rate = 0.0, ad_rate = 0.0, filament_plume = 0.0, ad_plume = 0.0;
  for (PlumeModel model : {PlumeModel::Filament, PlumeModel::AdvectionDiffusion}) {
    DatasetOptions o;
    o.maps = maps;
    o.sources = 100;
    o.seed = 1;
    o.plume.model = model;
    RunOptions run;
    run.threads = threads;
    const fs::path dir = out / to_string(model);
    fs::remove_all(dir);  // time a cold run: every flow solved
    const DatasetSummary s = generate_dataset(dir, o, run);
    const double per_sample_plume = s.plume_seconds / s.samples;  // thread-seconds
    std::printf(
        "%-20s %7.1f samples/s (flow included) | flow %.2f s/map | plume %.2f ms/sample "
        "(thread time) | wall %.1f s | thesis scale ~%.1f min\n",
        to_string(model), s.samples_per_second(), s.flow_seconds / s.maps, 1e3 * per_sample_plume,
        s.seconds, thesis_samples / s.samples_per_second() / 60.0);
    (model == PlumeModel::Filament ? filament_rate : ad_rate) = s.samples_per_second();
    (model == PlumeModel::Filament ? filament_plume : ad_plume) = per_sample_plume;
    fs::remove_all(dir);
  }
  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  std::printf("advection-diffusion vs filament: %.1fx samples/s with the flow, %.1fx per plume\n",
              ad_rate / filament_rate, filament_plume / ad_plume);
  std::printf(
      "peak resident memory: %.0f MB (independent of the number of maps: one map per "
      "thread in memory)\n",
      ru.ru_maxrss / 1024.0);
  return 0;
}
