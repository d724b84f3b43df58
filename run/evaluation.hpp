#pragma once
// The evaluation harness (thesis section 14.3.2): every ground-truth source of
// every map, `runs` times each from seeded random free starts, in parallel.
// Results do not depend on the thread count: run k's seed is a function of
// (seed, map, source, run) only, and records are kept in run order.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "core/seed.hpp"
#include "core/statistics.hpp"
#include "core/thread_pool.hpp"
#include "map/map.hpp"
#include "run/replay.hpp"
#include "run/scenario.hpp"

namespace plumekit::run {

struct EvaluationOptions {
  SteOptions ste;
  int runs = 3;  // per source, from seeded random free starts
  std::uint64_t seed = kDefaultSeed;
  // Seeds seed, seed + 1, ..., each a whole set of runs, pooled: more runs from
  // other starts and other plumes (the world's filaments and the sensor noise).
  int seeds = 1;
  // Runs in parallel, and the threads of each map's surrogate table build (it replaces
  // ste.threads); 0: one per core. Results do not depend on it.
  int threads = kDefaultThreads;
  int source_count = 0;  // 0: all of each map's sources; K: the first K (a labelled subset)
  // evaluation.shard K/N: only part K (0 <= K < N) of the (map, source) pairs, in order; the
  // parts are joined by merge_evaluation_parts (run/evaluation_parts.hpp).
  int part_k = 0, part_n = 1;
  // The run counts, the part and ste.validate(); evaluate() calls it before any work.
  void validate() const;
  // Sets part_k and part_n from "K/N"; OptionError naming evaluation.shard otherwise.
  void set_part(const std::string& k_of_n);
};

// The (map, source) pairs evaluated, numbered in map then source order, and the contiguous
// block [first, end) of them that part K of N runs: whole pairs keep each run's records
// together, and contiguous blocks let most parts build only a few maps' winds and tables.
struct PairRange {
  long long first = 0, end = 0, total = 0;
};
PairRange part_pairs(const std::vector<Map>& maps, const EvaluationOptions& options);

struct RunRecord {
  std::string map;
  int map_index = 0, source_index = 0, run = 0;
  std::uint64_t seed = kDefaultSeed;  // the evaluation seed this run belongs to
  Vec2 source, start, estimate;
  double error_m = 0.0;
  int samples = 0;
  double distance_m = 0.0, mission_s = 0.0, compute_s = 0.0, median_step_s = 0.0;
  std::string stopped_by;
  // The plume trackers' criteria (methods other than STE): a stop in the source box, and the
  // seeds' distance overhead (NaN where there was no detection or no progress).
  bool reached = false;
  double distance_overhead = std::numeric_limits<double>::quiet_NaN();
  MissionTimes times;         // the field's time metrics (run/mission_times.hpp)
  LocalizationResult result;  // kept for the example pictures
};

struct Stats {
  int runs = 0;
  double median_error_m = 0, mean_error_m = 0, success_0_5 = 0, success_1_0 = 0;
  Interval success_0_5_ci95, success_1_0_ci95;  // Wilson (core/statistics.hpp)
  double median_samples = 0, median_distance_m = 0, median_step_s = 0;
  double median_mission_s = 0;  // the robot's time to its estimate: travel and sampling
  double entropy_stops = 0;     // fraction stopped by the entropy rule
  double reached = 0;           // fraction that stopped in the source box
  Interval reached_ci95;
  // Over the runs that have one (NaN when none does), and how many do.
  double median_distance_overhead = std::numeric_limits<double>::quiet_NaN();
  int distance_overhead_runs = 0;
  // The time metrics (run/mission_times.hpp): each median over the runs that got there (NaN when
  // none did), and how many did; GSL-Bench's success rule over all runs.
  double median_first_detection_s = std::numeric_limits<double>::quiet_NaN();
  double median_within_1m_s = std::numeric_limits<double>::quiet_NaN();
  double median_within_0_5m_s = std::numeric_limits<double>::quiet_NaN();
  int detected_runs = 0, within_1m_runs = 0, within_0_5m_runs = 0;
  double median_over_optimum = std::numeric_limits<double>::quiet_NaN();
  double gsl_bench_success = 0;
  Interval gsl_bench_success_ci95;
};
Stats summarise(const std::vector<const RunRecord*>& runs);

struct MapReport {
  std::string name;
  MapFrame frame;  // for reporting positions in the map's frame
  Stats stats;
  double wind_s = 0, table_build_s = 0, wall_s = 0;  // 0 for a map this part did not run
};

struct EvaluationResult {
  std::string method = "ste";  // the registry's name
  // A plume tracker's evaluation: runs.csv and the summaries add the source box and the distance
  // overhead.
  bool tracking() const { return ends_on_arrival(method); }
  std::vector<RunRecord> runs;
  std::vector<MapReport> maps;
  Stats overall;
  double wall_s = 0;
  int seeds = 1;    // EvaluationOptions::seeds: runs.csv has a seed column when more than one
  PairRange pairs;  // what this result holds: all pairs, or one part's
  int threads = 1;  // the count used
  // How many methods ran together on the same runs (evaluate_methods): wall_s is then all of
  // theirs, and a method's own time is its model builds and its runs' decisions.
  int methods_together = 1;
  double decisions_s = 0;         // wall time of the decisions, summed over the runs
  double model_build_s() const {  // summed over the maps
    double s = 0;
    for (const MapReport& m : maps)
      s += m.table_build_s;
    return s;
  }
};

// `progress(done, total)` is called from the calling thread's perspective
// under a lock, after each run.
// `after_map` sees each map's scenario and records before the scenario goes
// (for pictures that need the wind).
using AfterMap = std::function<void(const Scenario&, const std::vector<RunRecord>&)>;
EvaluationResult evaluate(const std::vector<Map>& maps, const EvaluationOptions& options,
                          const std::function<void(int, int)>& progress = {},
                          const AfterMap& after_map = {});

// Every method of `kinds` (options.ste.method.name replaced by each) on the same runs, one
// result per method, each byte for byte (but its wall times) the result of evaluate() with that
// method alone. Each run's plume is simulated once and all the methods' robots sample it at once
// (world/shared_plume.hpp): the plume, most of a run's cost, is paid for the longest mission
// instead of for every method's. `progress` counts runs of all the methods; `after_map` is
// called for each method (its index in `kinds`) and map. The maps' and the whole wall times are
// the shared ones.
using AfterMethodMap =
    std::function<void(std::size_t method, const Scenario&, const std::vector<RunRecord>&)>;
// Given, every run's replay is recorded (run/replay_recorder.hpp: the same run, slower) and handed
// over on the run's thread, method by method, as soon as the run ends (`evaluate --replays`).
using ReplaySink = std::function<void(std::size_t method, const RunRecord&, const Replay&)>;
std::vector<EvaluationResult> evaluate_methods(const std::vector<Map>& maps,
                                               const EvaluationOptions& options,
                                               const std::vector<std::string>& kinds,
                                               const std::function<void(int, int)>& progress = {},
                                               const AfterMethodMap& after_map = {},
                                               const ReplaySink& replays = {});

// CSV of all runs (one header line, one line per run): what each run found, the same bytes
// whatever the threads, the machine or the --shard split. The measured compute times are in
// timings_csv, with the same first columns.
std::string runs_csv(const EvaluationResult& result);
std::string timings_csv(const EvaluationResult& result);

}  // namespace plumekit::run
