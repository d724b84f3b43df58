// Issue 45's speed target ("A fast world"): the world step at least 5x faster than the world before
// it, on the nine test maps and on a 20 x 20 m building, with the filaments alive at the default
// release rate and the mox-fast gas sensor. The named baseline is PlumeEngine::V1 (the old world,
// bit for bit: set_world "faithful-v1"), the library PlumeEngine::Fast ("faithful"); both are
// measured in the same run, interleaved map by map, and the last table prints baseline / library
// (bench/baseline_ratio.hpp; >1: the fast engine is faster). Per map three pairs:
//
//   WorldStep/{baseline,library}/<map>   one reading interval of a travelling robot (0.1 s: the
//                                        plume steps twice, the sensor reads once), through
//                                        SimulatedWorld::pass, as a run does it
//   PlumeStep/{baseline,library}/<map>   FilamentSimulation::step() alone (one 0.05 s step)
//   SensorRead/{baseline,library}/<map>  one FilamentSimulation::concentration_at 0.5 m downwind
//                                        of the source, in a plume that does not move meanwhile
//
// so that a reader sees where the world step's speed comes from. WorldStep also holds what the
// other two leave out: the fast engine's spatial index, built by the first read after a step, and
// the sensor's response. <map> 0-8 are data/test-maps/*.json by name, 9 the building; the label
// names the map and the filaments alive after the spin-up (also the counter "filaments").
//
//   build/bench/world_bench [--benchmark_filter=WorldStep] [--benchmark_repetitions=N] ...
//
// Five repetitions by default, reported as aggregates, and the ratios are those of the medians:
// main() puts --benchmark_repetitions=5 --benchmark_report_aggregates_only=true before the
// command line's flags, which override them. Times are CPU times (both engines use one thread).
// Each map's flow is solved once and each world spun up once (outside the timing); the worlds
// then run on from call to call, statistically steady.
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "bench/baseline_ratio.hpp"
#include "cfd/flow_policy.hpp"
#include "core/geometry.hpp"
#include "dataset/random_maps.hpp"
#include "map/map_json.hpp"
#include "world/filament_model.hpp"
#include "world/gas_sensor.hpp"
#include "world/random_streams.hpp"
#include "world/shared_plume.hpp"
#include "world/simulated_world.hpp"

using namespace plumekit;
namespace fs = std::filesystem;

namespace {

constexpr std::uint64_t kBuildingSeed = 1001;  // scripts/compare-methods.sh's building seed
constexpr double kTravelSpeed = 0.5;           // m/s, WorldOptions::speed
constexpr double kPathLength = 3.0;            // m downwind of the source
constexpr double kPathStep = 0.1;              // m, the streamline's integration step
constexpr double kReadDistance = 0.5;          // m downwind of the source, SensorRead's point

struct Arena {
  Map map;
  cfd::WindField wind;
  Vec2 source;
  // The robot's path: down the mean plume's centreline from the source and back to it.
  std::vector<Vec2> path;
  double path_length = 0.0;
  Vec2 read_point;  // SensorRead's
};

std::vector<fs::path> test_map_files() {
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(fs::path(PLUMEKIT_DATA_DIR) / "test-maps"))
    if (e.path().extension() == ".json") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

// The streamline of the steady wind from the source, up to kPathLength or until it meets an
// obstacle, a wall or still air: where the plume's mean runs, so that the robot reads in the
// plume, where the filaments are dense and reading costs most (a path upwind of the source would
// flatter the fast engine, whose index skips empty buckets).
std::vector<Vec2> centreline(const Map& map, const cfd::WindField& wind, Vec2 source) {
  std::vector<Vec2> line{source};
  for (double s = 0.0; s < kPathLength - 1e-9; s += kPathStep) {
    const Vec2 w = wind.at(line.back());
    const double speed = norm(w);
    if (speed < 1e-6) break;
    const Vec2 next = line.back() + (kPathStep / speed) * w;
    if (!map.is_free(next)) break;
    line.push_back(next);
  }
  return line;
}

// The 20 x 20 m building: map 0 of the building family drawn from kBuildingSeed at that size. Its
// source is drawn as `plumekit maps random --sources 1` draws it (random_sources, 0.1 m from
// every obstacle and wall, the same seed and index): deterministic, and in the flow's air.
Map building_map() {
  dataset::RandomMapOptions o;
  o.families = {"building"};
  o.building_min_size = o.building_max_size = 20.0;
  Map map = dataset::random_map(o, kBuildingSeed, 0).map;
  if (map.sources.empty()) map.sources = dataset::random_sources(map, 1, 0.1, kBuildingSeed, 0);
  return map;
}

// Map `i` with its flow solved (once per process) and the robot's path. The test maps' flow at
// 0.05 m cells, the building's at 0.1 m (as scripts/compare-methods.sh solves buildings).
const Arena& arena(int i) {
  static std::map<int, std::unique_ptr<Arena>> cache;
  auto& slot = cache[i];
  if (slot) return *slot;
  static const std::vector<fs::path> files = test_map_files();
  const bool building = i == static_cast<int>(files.size());
  auto a = std::make_unique<Arena>();
  a->map = building ? building_map() : read_map(files.at(static_cast<std::size_t>(i)));
  cfd::FlowOptions flow;
  flow.cell = building ? 0.1 : 0.05;
  a->wind = cfd::solve_wind(a->map, flow).flow.wind;
  a->source = a->map.sources.at(0);
  const std::vector<Vec2> line = centreline(a->map, a->wind, a->source);
  a->path = line;
  a->path.insert(a->path.end(), line.rbegin() + 1, line.rend());
  for (std::size_t k = 1; k < a->path.size(); ++k)
    a->path_length += norm(a->path[k] - a->path[k - 1]);
  a->read_point = point_along(line, kReadDistance);
  slot = std::move(a);
  return *slot;
}

world::WorldOptions world_options(bool v1) {
  world::WorldOptions o;
  world::set_world(o.filament, v1 ? "faithful-v1" : "faithful");
  o.speed = kTravelSpeed;
  o.sensor = world::gas_sensor_preset("mox-fast");
  return o;
}

std::uint64_t seed_of(int i) {
  return world::run_seed(45, static_cast<std::uint64_t>(i), 0, 0);
}

// A robot's world on map `i`, spun up once. Built as a one-robot SharedPlume and the world in it,
// which is what SimulatedWorld(map, wind, source, options, seed) does inside, so that the
// filaments after the spin-up can be counted without a second spin-up.
struct WorldCase {
  std::unique_ptr<world::SharedPlume> plume;
  std::unique_ptr<world::SimulatedWorld> world;
  std::size_t filaments = 0;  // after the spin-up
  double along = 0.0;         // the robot's distance along the path, wrapping round
};

WorldCase& world_case(int i, bool v1) {
  static std::map<std::pair<int, bool>, std::unique_ptr<WorldCase>> cache;
  auto& slot = cache[{i, v1}];
  if (slot) return *slot;
  const Arena& a = arena(i);
  const world::WorldOptions o = world_options(v1);
  auto c = std::make_unique<WorldCase>();
  c->plume =
      std::make_unique<world::SharedPlume>(a.map, a.wind, a.source, o.filament, seed_of(i), 1);
  c->world = std::make_unique<world::SimulatedWorld>(*c->plume, 0, a.map, a.source, o, seed_of(i));
  c->filaments = c->plume->at(c->world->steps(), 0).filament_count();
  slot = std::move(c);
  return *slot;
}

// The plume alone on map `i`, spun up once (the same options and seed as the world's plume).
struct PlumeCase {
  std::unique_ptr<world::FilamentSimulation> sim;
  std::size_t filaments = 0;  // after the spin-up
};

PlumeCase& plume_case(int i, bool v1) {
  static std::map<std::pair<int, bool>, std::unique_ptr<PlumeCase>> cache;
  auto& slot = cache[{i, v1}];
  if (slot) return *slot;
  const Arena& a = arena(i);
  const world::FilamentOptions o = world_options(v1).filament;
  auto c = std::make_unique<PlumeCase>();
  c->sim = std::make_unique<world::FilamentSimulation>(a.map, a.wind, a.source, o, seed_of(i));
  world::spin_up(*c->sim, o);
  c->filaments = c->sim->filament_count();
  slot = std::move(c);
  return *slot;
}

void label(benchmark::State& state, int i, std::size_t filaments) {
  state.SetLabel(arena(i).map.name + ", " + std::to_string(filaments) + " filaments");
  state.counters["filaments"] = static_cast<double>(filaments);
}

void world_step(benchmark::State& state, bool v1) {
  const int i = static_cast<int>(state.range(0));
  const Arena& a = arena(i);
  WorldCase& c = world_case(i, v1);
  const double step = kTravelSpeed * c.world->reading_interval();
  for (auto _ : state) {
    c.world->pass(a.path, c.along);
    c.along = a.path_length > 0.0 ? std::fmod(c.along + step, a.path_length) : 0.0;
  }
  label(state, i, c.filaments);
}

void plume_step(benchmark::State& state, bool v1) {
  const int i = static_cast<int>(state.range(0));
  PlumeCase& c = plume_case(i, v1);
  for (auto _ : state)
    c.sim->step();
  label(state, i, c.filaments);
}

void sensor_read(benchmark::State& state, bool v1) {
  const int i = static_cast<int>(state.range(0));
  const Vec2 p = arena(i).read_point;
  PlumeCase& c = plume_case(i, v1);
  // The first read after a step builds the fast engine's index; this benchmark times the reads.
  benchmark::DoNotOptimize(c.sim->concentration_at(p));
  for (auto _ : state)
    benchmark::DoNotOptimize(c.sim->concentration_at(p));
  label(state, i, c.filaments);
}

// OpenBLAS (UMFPACK's BLAS, in the flow solver) chooses its kernels when it is loaded, before
// main(), from OPENBLAS_CORETYPE or else its own CPU detection, which on the development machine's
// AMD EPYC picks Cooperlake. Its kernels round differently per core type, so the solved winds,
// and with them the plumes, would differ from those the project's results use (SkylakeX;
// results/methods-test-maps/README.md). Setting the variable in main() is too late for a library
// loaded at start-up, so the process starts itself again with it set. A value already set wins.
void pin_openblas_coretype(char** argv) {
  if (std::getenv("OPENBLAS_CORETYPE") != nullptr) return;
  setenv("OPENBLAS_CORETYPE", "SkylakeX", 0);
  // The executable's own path, not /proc/self/exe, so that ps and top still show its name.
  char exe[4096];
  const ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
  if (n <= 0) return;
  exe[n] = '\0';
  execv(exe, argv);  // returns only on failure: then run as we are
}

void register_benchmarks(int maps) {
  using Fn = void (*)(benchmark::State&, bool);
  const std::pair<const char*, Fn> kinds[] = {
      {"WorldStep", world_step}, {"PlumeStep", plume_step}, {"SensorRead", sensor_read}};
  // Map by map, baseline then library, so that each pair runs close together in time.
  for (int i = 0; i < maps; ++i)
    for (const auto& [name, fn] : kinds)
      for (const bool v1 : {true, false})
        benchmark::RegisterBenchmark((std::string(name) + (v1 ? "/baseline" : "/library")).c_str(),
                                     fn, v1)
            ->Arg(i)
            ->Unit(benchmark::kMicrosecond);
}

}  // namespace

int main(int argc, char** argv) {
  pin_openblas_coretype(argv);
  // Defaults first, so that the same flags on the command line override them.
  std::vector<char*> args{argv[0]};
  std::string repetitions = "--benchmark_repetitions=5";
  std::string aggregates = "--benchmark_report_aggregates_only=true";
  args.push_back(repetitions.data());
  args.push_back(aggregates.data());
  args.insert(args.end(), argv + 1, argv + argc);
  int n = static_cast<int>(args.size());
  args.push_back(nullptr);  // argv's end, as main's
  register_benchmarks(static_cast<int>(test_map_files().size()) + 1);
  return plumekit_bench::run_with_ratios(n, args.data());
}
