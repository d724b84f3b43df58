// STE speed on the test maps: the per-map table build (1 and 2 threads) and the
// compute per decision step of each plume model, against the baseline the
// thesis code had: running the CNN for every candidate source at every step.
//
//   build/bench/ste_bench [MODEL.pkcnn] [MAP.json]
//
// MODEL defaults to data/models/plume-unet.pkcnn, else the random-weight golden
// model (same architecture, so the same cost). Timings are wall clock; run it
// on a quiet machine, or compare only the ratios printed.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <vector>

#include "core/statistics.hpp"
#include "map/map_json.hpp"
#include "run/scenario.hpp"
#include "ste/surrogate_plume.hpp"
#include "surrogate/network.hpp"
#include "surrogate/plume_network.hpp"

using namespace plumekit;
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

namespace {

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// CPU seconds of the whole process (all threads).
double process_cpu() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// Median compute per decision step over runs from a few sources.
double step_median(const run::Scenario& sc, int runs) {
  std::vector<double> steps;
  for (int r = 0; r < runs; ++r) {
    const Vec2 source = sc.map().sources[r % sc.map().sources.size()];
    const std::uint64_t seed = world::run_seed(1, 0, r, 0);
    const run::LocalizationResult res = sc.run(source, sc.random_start(source, seed), seed);
    for (const run::Step& s : res.steps)
      steps.push_back(s.compute_s);
  }
  return median(steps);
}

}  // namespace

int main(int argc, char** argv) {
  fs::path model = fs::path(PLUMEKIT_DATA_DIR) / "models" / "plume-unet.pkcnn";
  if (!fs::exists(model)) model = fs::path(PLUMEKIT_TEST_DATA) / "surrogate" / "real.pkcnn";
  if (argc > 1) model = argv[1];
  const fs::path map_file = argc > 2
                                ? fs::path(argv[2])
                                : fs::path(PLUMEKIT_DATA_DIR) / "test-maps" / "test-4-l-shape.json";
  const Map map = read_map(map_file);
  std::printf("map %s, model %s\n", map.name.c_str(), model.string().c_str());

  // Table build, 1 and 2 threads.
  double build[2] = {0, 0}, cpu[2] = {0, 0};
  std::size_t cells = 0;
  for (int threads : {1, 2}) {
    ste::SurrogatePlumeOptions o;
    o.model = model;
    o.threads = threads;
    const auto t0 = Clock::now();
    const double c0 = process_cpu();
    const ste::SurrogatePlume table(map, o);
    build[threads - 1] = seconds_since(t0);
    cpu[threads - 1] = process_cpu() - c0;
    cells = std::count(table.allowed().begin(), table.allowed().end(), 1);
  }
  std::printf(
      "surrogate table: %zu source cells, build wall %.2f s on 1 thread, %.2f s on 2 "
      "(x%.2f); CPU %.2f s and %.2f s (%.1f ms per forward pass)\n",
      cells, build[0], build[1], build[0] / build[1], cpu[0], cpu[1], 1000 * cpu[0] / cells);

  // Decision steps, one thread each.
  const int runs = 5;
  for (run::PlumeModelKind kind : {run::PlumeModelKind::Surrogate, run::PlumeModelKind::Physics,
                                   run::PlumeModelKind::Gaussian}) {
    run::SteOptions o;
    o.model = kind;
    o.model_path = model.string();  // the likelihood follows the model (run::default_likelihood)
    o.threads = 2;
    const run::Scenario sc(map, o);
    std::printf("%-9s median compute per decision step %.2f ms CPU (%d runs; model build %.2f s)\n",
                to_string(kind), 1000 * step_median(sc, runs), runs, sc.model_build_s());
  }

  // The baseline: no table, the CNN run for every candidate source at each step
  // (the thesis code's approach, minus its model reloading). One forward pass
  // timed at batch 32 on one thread, times the cells.
  auto net = std::make_shared<const surrogate::Network>(surrogate::Network::load(model));
  const surrogate::PlumeNetwork plume(net, map);
  std::vector<Vec2> batch(32, map.sources[0]);
  plume.predict_batch(batch);  // warm-up
  const double c0 = process_cpu();
  plume.predict_batch(batch);
  const double per_pass = (process_cpu() - c0) / batch.size();  // CPU: load-independent
  run::SteOptions o;
  o.model = run::PlumeModelKind::Surrogate;
  o.model_path = model.string();
  const run::Scenario sc(map, o);
  const double with_table = step_median(sc, runs);
  // Each step updates with one sample and scores up to 8 candidates: each
  // needs every cell's reading there, which one forward pass per cell gives
  // for all points of its plume at once, so one pass per cell per step.
  const double without = per_pass * cells;
  std::printf(
      "baseline (CNN per candidate source per step): %.1f ms CPU per pass x %zu cells = %.2f s "
      "per step; the table makes a step x%.0f faster\n",
      1000 * per_pass, cells, without, without / with_table);
}
