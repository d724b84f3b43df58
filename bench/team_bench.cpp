// Issue 21's speed target for robot teams: the median CPU time of one robot's decision step
// (estimation, virtual samples, navigation, planning, task swap) for teams of 1-3 robots with each
// strategy, against the robot alone measured in the same run (the named baseline). The target is
// at most 0.1 s per robot with 3 collaborative robots. Plume models: physics (plumekit's open-field
// default for teams) and gaussian (the thesis's, Metropolis-Hastings: a collaborative decision
// runs a second chain with the virtual samples).
//
//   build/bench/team_bench [MAP.json] [RUNS]      # default: data/maps/empty.json, 3 runs
//
// Times are the thread's CPU time (what `evaluate` reports as step_ms), so load matters little.
#include <cstdio>
#include <filesystem>
#include <vector>

#include "core/statistics.hpp"
#include "map/map_json.hpp"
#include "run/scenario.hpp"

using namespace plumekit;
namespace fs = std::filesystem;

namespace {

// Every robot's decision steps over `runs` runs from the map's sources in turn.
double step_median(const Map& map, const run::SteOptions& o, int runs, std::size_t& steps_out) {
  const run::Scenario sc(map, o);
  std::vector<double> steps;
  for (int r = 0; r < runs; ++r) {
    const Vec2 source = map.sources[r % map.sources.size()];
    const std::uint64_t seed = world::run_seed(1, 0, r, 0);
    const run::LocalizationResult res = sc.run(source, sc.random_start(source, seed), seed);
    if (res.team.empty())
      for (const run::Step& s : res.steps)
        steps.push_back(s.compute_s);
    for (const run::TeamRobot& t : res.team)
      for (const run::Step& s : t.steps)
        steps.push_back(s.compute_s);
  }
  steps_out = steps.size();
  return median(steps);
}

}  // namespace

int main(int argc, char** argv) {
  const fs::path map_file =
      argc > 1 ? fs::path(argv[1]) : fs::path(PLUMEKIT_DATA_DIR) / "maps" / "empty.json";
  const int runs = argc > 2 ? std::atoi(argv[2]) : 3;
  const Map map = read_map(map_file);
  std::printf("map %s, %d runs per team, median CPU per robot decision step\n", map.name.c_str(),
              runs);
  for (run::PlumeModelKind model : {run::PlumeModelKind::Physics, run::PlumeModelKind::Gaussian}) {
    run::SteOptions base;
    base.model = model;
    world::set_world(base.world.filament, "thesis");
    std::size_t steps = 0;
    const double alone = step_median(map, base, runs, steps);
    std::printf("%-8s 1 robot          %8.2f ms  (baseline, %zu steps)\n", to_string(model),
                1000 * alone, steps);
    for (run::TeamStrategy s : {run::TeamStrategy::Individualist, run::TeamStrategy::Cooperative,
                                run::TeamStrategy::Collaborative})
      for (int robots : {2, 3}) {
        run::SteOptions o = base;
        o.team.robots = robots;
        o.team.strategy = s;
        const double t = step_median(map, o, runs, steps);
        std::printf("%-8s %-13s %d %8.2f ms  %5.2fx the baseline (%zu steps)\n", to_string(model),
                    to_string(s), robots, 1000 * t, t / alone, steps);
      }
  }
}
