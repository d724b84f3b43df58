// Issue 20's speed figures: the median compute of one decision step of every localization method
// on the thesis's test maps (one core each), against STE with the physics model measured in the
// same run (the named baseline), and Kernel DM+V on a 10 x 4 m map from 100 samples.
//
//   build/bench/methods_bench [MAP.json] [RUNS]
//
// Times are the thread's CPU time (what `evaluate` reports as step_ms), so load matters little.
#include <cstdio>
#include <filesystem>
#include <random>
#include <vector>

#include "core/random.hpp"
#include "core/statistics.hpp"
#include "map/map_json.hpp"
#include "methods/kernel_dmv.hpp"
#include "run/method_run.hpp"
#include "run/scenario.hpp"

using namespace plumekit;
namespace fs = std::filesystem;

namespace {

// The median step compute of `runs` runs from the map's sources in turn; also the stops.
double step_median(const Map& map, const run::SteOptions& o, int runs, std::size_t& stops) {
  const run::Scenario sc(map, o);
  std::vector<double> steps;
  for (int r = 0; r < runs; ++r) {
    const Vec2 source = map.sources[r % map.sources.size()];
    const std::uint64_t seed = world::run_seed(1, 0, r, 0);
    const run::LocalizationResult res = sc.run(source, sc.random_start(source, seed), seed);
    for (const run::Step& s : res.steps)
      steps.push_back(s.compute_s);
  }
  stops = steps.size();
  return median(steps);
}

// Kernel DM+V of 100 random readings on the map, median of 50 builds.
double gdm_median(const Map& map) {
  std::mt19937_64 rng(7);
  std::vector<methods::Sample> samples;
  while (samples.size() < 100) {
    const Vec2 p{uniform(rng, 0.0, map.width), uniform(rng, 0.0, map.height)};
    if (map.is_free(p)) samples.push_back({p, uniform(rng, 0.0, 1000.0), Vec2{1.0, 0.0}});
  }
  methods::GdmOptions o;
  o.wind_stretch = 0.6;  // DM+V/W: the dearer of the two
  std::vector<double> t;
  for (int k = 0; k < 50; ++k) {
    const double t0 = run::thread_cpu_s();
    const methods::GdmMaps maps = methods::kernel_dmv(map, samples, o);
    t.push_back(run::thread_cpu_s() - t0);
    if (maps.samples != 100) std::abort();
  }
  return median(t);
}

}  // namespace

int main(int argc, char** argv) {
  const fs::path map_file = argc > 1
                                ? fs::path(argv[1])
                                : fs::path(PLUMEKIT_DATA_DIR) / "test-maps" / "test-4-l-shape.json";
  const int runs = argc > 2 ? std::atoi(argv[2]) : 5;
  const Map map = read_map(map_file);
  std::printf("map %s, %d runs per method, median CPU per decision step\n", map.name.c_str(), runs);
  run::SteOptions base;
  base.model = run::PlumeModelKind::Physics;
  std::size_t stops = 0;
  const double ste = step_median(map, base, runs, stops);
  std::printf("%-16s %8.3f ms  (baseline, %zu steps)\n", "ste (physics)", 1000 * ste, stops);
  for (const std::string& name : run::method_names()) {
    if (name == "ste") continue;
    run::SteOptions o = base;
    o.method.name = name;
    const double t = step_median(map, o, runs, stops);
    std::printf("%-16s %8.3f ms  %7.4fx the baseline (%zu steps)\n", name.c_str(), 1000 * t,
                t / ste, stops);
  }
  std::printf("Kernel DM+V/W, 100 samples, 0.1 m cells: %.2f ms\n", 1000 * gdm_median(map));
}
