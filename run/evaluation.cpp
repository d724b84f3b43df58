#include "run/evaluation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <iomanip>
#include <memory>
#include <mutex>
#include <sstream>
#include <thread>

#include "core/csv.hpp"
#include "core/error.hpp"
#include "core/statistics.hpp"
#include "methods/plume_tracking.hpp"
#include "run/replay_recorder.hpp"
#include "world/shared_plume.hpp"

namespace plumekit::run {

namespace {

using Clock = std::chrono::steady_clock;

int sources_evaluated(const Map& map, const EvaluationOptions& o) {
  const int all = static_cast<int>(map.sources.size());
  return o.source_count > 0 ? std::min(o.source_count, all) : all;
}

// The records of one map, in run order (source, then seed, then run), before they are run: the
// sources whose pair number (`first_pair` + source index) lies in `part`.
std::vector<RunRecord> planned_runs(const Map& map, int map_index, const EvaluationOptions& o,
                                    long long first_pair, const PairRange& part) {
  const int n_src = sources_evaluated(map, o);
  std::vector<RunRecord> records;
  for (int s = 0; s < n_src; ++s) {
    if (first_pair + s < part.first || first_pair + s >= part.end) continue;
    for (int k = 0; k < o.seeds; ++k)
      for (int r = 0; r < o.runs; ++r) {
        RunRecord& rec = records.emplace_back();
        rec.map = map.name;
        rec.map_index = map_index;
        rec.source_index = s;
        rec.run = r;
        rec.seed = o.seed + static_cast<std::uint64_t>(k);
        rec.source = map.sources[s];
      }
  }
  return records;
}

// The seeds' distance overhead of a run (seed 000 App. C): the path from its first stop above
// the detection threshold on. NaN when no stop detected or the robot made no progress.
double tracking_overhead(const LocalizationResult& r, Vec2 source, double threshold) {
  std::size_t first = 0;
  while (first < r.steps.size() && !(r.steps[first].value > threshold))
    ++first;
  if (first == r.steps.size()) return std::numeric_limits<double>::quiet_NaN();
  std::vector<Vec2> path{r.steps[first].position};
  for (std::size_t k = first + 1; k < r.steps.size(); ++k)
    for (std::size_t i = 1; i < r.steps[k].path_in.size(); ++i)
      path.push_back(r.steps[k].path_in[i]);
  return methods::distance_overhead(path, source)
      .value_or(std::numeric_limits<double>::quiet_NaN());
}

// A run's summary columns, from its result.
void fill_record(const Scenario& scenario, RunRecord& rec) {
  const LocalizationResult& r = rec.result;
  rec.estimate = r.estimate;
  rec.error_m = norm(r.estimate - rec.source);
  rec.samples = r.samples;
  rec.distance_m = r.distance_m;
  rec.mission_s = r.time_s;
  rec.compute_s = r.compute_s;
  rec.median_step_s = r.median_step_s;
  rec.stopped_by = r.stopped_by;
  rec.reached = r.reached;
  rec.times = r.times;
  if (ends_on_arrival(scenario.options().method.name))
    rec.distance_overhead =
        tracking_overhead(r, rec.source, scenario.options().method.tracking.detection_threshold);
}

// The run's replay recorder for `scenario`'s robots, when replays are wanted.
// `slot`: the method's robot's number in a plume several methods share.
std::unique_ptr<ReplayRecorder> recorder_for(const Scenario& scenario, const ReplaySink& replays,
                                             int slot = 0) {
  return replays ? replay_recorder_for(scenario, slot) : nullptr;
}

// Hands method m's replay of `rec` to the sink.
void hand_replay(const ReplaySink& replays, std::size_t m, const Scenario& scenario,
                 ReplayRecorder* recorder, const RunRecord& rec) {
  if (!recorder) return;
  std::ostringstream title;
  title << std::fixed << std::setprecision(2) << rec.map << ": " << scenario.options().method.name
        << ", source " << rec.source_index << " (" << rec.source.x << ", " << rec.source.y
        << "), run " << rec.run << ", seed " << rec.seed;
  replays(m, rec, recorder->finish(rec.result, rec.source, title.str()));
}

// Run k of every method (records[m][k] with scenarios[m]), from the map's starts or its seeded
// random start. Several methods share the run's plume, each robot on its own thread
// (world/shared_plume.hpp): each reads what it would alone.
void run_one(const std::vector<std::unique_ptr<Scenario>>& scenarios,
             std::vector<std::vector<RunRecord>>& records, std::size_t k,
             const ReplaySink& replays) {
  const Scenario& first = *scenarios.front();
  RunRecord& head = records.front()[k];
  const std::uint64_t s = world::run_seed(head.seed, head.map_index, head.source_index, head.run);
  const Vec2 start =
      first.run_start(head.source, head.run, world::stream_seed(s, world::SteStream::Start));
  if (scenarios.size() == 1) {
    const std::unique_ptr<ReplayRecorder> recorder = recorder_for(first, replays);
    head.start = start;
    head.result = first.run(head.source, start, s, recorder.get());
    fill_record(first, head);
    hand_replay(replays, 0, first, recorder.get(), head);
    return;
  }
  first.check_source(head.source);
  world::SharedPlume plume(first.map(), first.wind(), head.source, first.options().world.filament,
                           s, static_cast<int>(scenarios.size()));
  // The first method's recorder watches the plume for all (it steps to the longest mission).
  std::vector<std::unique_ptr<ReplayRecorder>> recorders;
  for (std::size_t m = 0; m < scenarios.size(); ++m)
    recorders.push_back(recorder_for(*scenarios[m], replays, static_cast<int>(m)));
  if (recorders.front()) plume.watch(recorders.front().get());
  std::vector<std::exception_ptr> failed(scenarios.size());
  auto robot = [&](std::size_t m) {
    try {
      RunRecord& rec = records[m][k];
      world::SimulatedWorld world(plume, static_cast<int>(m), first.map(), rec.source,
                                  scenarios[m]->options().world, s);
      rec.start = start;
      rec.result = scenarios[m]->run(world, start, s, recorders[m].get());
      fill_record(*scenarios[m], rec);
    } catch (...) {
      failed[m] = std::current_exception();
    }
  };
  std::vector<std::thread> others;
  for (std::size_t m = 1; m < scenarios.size(); ++m) {
    try {
      others.emplace_back(robot, m);
    } catch (...) {  // no thread for robot m: it and those after it never join the plume
      failed[m] = std::current_exception();
      for (std::size_t r = m; r < scenarios.size(); ++r)
        plume.leave(static_cast<int>(r));
      break;
    }
  }
  robot(0);
  for (std::thread& t : others)
    t.join();
  plume.watch(nullptr);
  for (const std::exception_ptr& e : failed)
    if (e) std::rethrow_exception(e);
  for (std::size_t m = 0; m < scenarios.size(); ++m) {
    if (recorders[m]) recorders[m]->copy_plume_frames(*recorders.front());
    hand_replay(replays, m, *scenarios[m], recorders[m].get(), records[m][k]);
  }
}

std::vector<const RunRecord*> pointers(const std::vector<RunRecord>& records) {
  std::vector<const RunRecord*> p;
  for (const RunRecord& r : records)
    p.push_back(&r);
  return p;
}

// The columns that name a run, first in runs.csv and timings.csv.
void run_id_columns(std::ostream& s, const RunRecord& r) {
  s << csv_field(r.map) << ',' << r.source_index << ',' << r.run;
}

}  // namespace

PairRange part_pairs(const std::vector<Map>& maps, const EvaluationOptions& o) {
  PairRange p;
  for (const Map& m : maps)
    p.total += sources_evaluated(m, o);
  p.first = p.total * o.part_k / o.part_n;
  p.end = p.total * (o.part_k + 1) / o.part_n;
  return p;
}

namespace {

// The median of the finite values of `values` (NaN when none), and how many there are.
double median_of_finite(const std::vector<double>& values, int& count) {
  std::vector<double> finite;
  for (double v : values)
    if (std::isfinite(v)) finite.push_back(v);
  count = static_cast<int>(finite.size());
  return finite.empty() ? std::numeric_limits<double>::quiet_NaN() : median(finite);
}

void summarise_times(const std::vector<const RunRecord*>& runs, Stats& s) {
  std::vector<double> detection, within_1m, within_0_5m, over;
  int gsl = 0, with_optimum = 0;
  for (const RunRecord* r : runs) {
    detection.push_back(r->times.first_detection_s);
    within_1m.push_back(r->times.within_1m_s);
    within_0_5m.push_back(r->times.within_0_5m_s);
    over.push_back(r->times.over_optimum());
    gsl += r->times.gsl_bench_success();
  }
  s.median_first_detection_s = median_of_finite(detection, s.detected_runs);
  s.median_within_1m_s = median_of_finite(within_1m, s.within_1m_runs);
  s.median_within_0_5m_s = median_of_finite(within_0_5m, s.within_0_5m_runs);
  s.median_over_optimum = median_of_finite(over, with_optimum);
  s.gsl_bench_success_ci95 = wilson_interval(gsl, s.runs);
  s.gsl_bench_success = gsl / static_cast<double>(s.runs);
}

}  // namespace

Stats summarise(const std::vector<const RunRecord*>& runs) {
  Stats s;
  s.runs = static_cast<int>(runs.size());
  if (runs.empty()) return s;
  summarise_times(runs, s);
  std::vector<double> err, samples, dist, step, mission, overhead;
  double sum = 0;
  for (const RunRecord* r : runs) {
    err.push_back(r->error_m);
    samples.push_back(r->samples);
    dist.push_back(r->distance_m);
    mission.push_back(r->mission_s);
    step.push_back(r->median_step_s);
    sum += r->error_m;
    s.success_0_5 += r->error_m <= 0.5;
    s.success_1_0 += r->error_m <= 1.0;
    s.entropy_stops += r->stopped_by == "entropy";
    s.reached += r->reached;
    if (std::isfinite(r->distance_overhead)) overhead.push_back(r->distance_overhead);
  }
  s.reached_ci95 = wilson_interval(static_cast<int>(s.reached), s.runs);
  s.reached /= static_cast<double>(runs.size());
  s.distance_overhead_runs = static_cast<int>(overhead.size());
  if (!overhead.empty()) s.median_distance_overhead = median(overhead);
  const double n = static_cast<double>(runs.size());
  s.success_0_5_ci95 = wilson_interval(static_cast<int>(s.success_0_5), s.runs);
  s.success_1_0_ci95 = wilson_interval(static_cast<int>(s.success_1_0), s.runs);
  s.median_error_m = median(err);
  s.mean_error_m = sum / n;
  s.success_0_5 /= n;
  s.success_1_0 /= n;
  s.entropy_stops /= n;
  s.median_samples = median(samples);
  s.median_distance_m = median(dist);
  s.median_mission_s = median(mission);
  s.median_step_s = median(step);
  return s;
}

namespace {

// Each method's STE options: the evaluation's, with the method and the evaluation's threads.
std::vector<SteOptions> method_options(const EvaluationOptions& o,
                                       const std::vector<std::string>& kinds) {
  std::vector<SteOptions> ste(kinds.size(), o.ste);
  for (std::size_t m = 0; m < kinds.size(); ++m) {
    ste[m].method.name = kinds[m];
    ste[m].threads = o.threads;  // the table build uses the evaluation's threads
    ste[m].validate();
  }
  return ste;
}

// Each method's result before any map: what it is and which part of the pairs it covers.
std::vector<EvaluationResult> empty_results(const EvaluationOptions& o,
                                            const std::vector<std::string>& kinds,
                                            const PairRange& pairs) {
  std::vector<EvaluationResult> results(kinds.size());
  for (std::size_t m = 0; m < kinds.size(); ++m) {
    results[m].method = kinds[m];
    results[m].seeds = o.seeds;
    results[m].pairs = pairs;
    results[m].methods_together = static_cast<int>(kinds.size());
  }
  return results;
}

// One scenario per method on `map`; the later ones share the first one's wind and plume.
std::vector<std::unique_ptr<Scenario>> method_scenarios(const Map& map,
                                                        const std::vector<SteOptions>& ste) {
  std::vector<std::unique_ptr<Scenario>> scenarios;
  for (std::size_t m = 0; m < ste.size(); ++m)
    scenarios.push_back(m == 0 ? std::make_unique<Scenario>(map, ste[m])
                               : std::make_unique<Scenario>(map, ste[m], *scenarios[0]));
  return scenarios;
}

// Adds one map's report and runs (moved out of `records`) to each method's result.
void add_map(const MapReport& report, double wall_s,
             const std::vector<std::unique_ptr<Scenario>>& scenarios,
             std::vector<std::vector<RunRecord>>& records, const AfterMethodMap& after_map,
             std::vector<EvaluationResult>& results) {
  for (std::size_t m = 0; m < results.size(); ++m) {
    MapReport r = report;
    r.wind_s = scenarios[m]->wind_s();
    r.table_build_s = scenarios[m]->model_build_s();
    r.stats = summarise(pointers(records[m]));
    r.wall_s = wall_s;
    results[m].maps.push_back(r);
    if (after_map) after_map(m, *scenarios[m], records[m]);
    for (RunRecord& run : records[m]) {
      results[m].decisions_s += run.result.decisions_s;
      results[m].runs.push_back(std::move(run));
    }
  }
}

}  // namespace

std::vector<EvaluationResult> evaluate_methods(const std::vector<Map>& maps,
                                               const EvaluationOptions& o,
                                               const std::vector<std::string>& kinds,
                                               const std::function<void(int, int)>& progress,
                                               const AfterMethodMap& after_map,
                                               const ReplaySink& replays) {
  o.validate();
  if (kinds.empty()) throw std::logic_error("evaluate_methods: no method");
  const auto t_all = Clock::now();
  for (const Map& m : maps)
    if (m.sources.empty())
      throw InputError("map " + m.name + " has no ground-truth \"sources\" to evaluate on");
  const PairRange pairs = part_pairs(maps, o);
  const std::vector<SteOptions> ste = method_options(o, kinds);
  std::vector<EvaluationResult> results = empty_results(o, kinds, pairs);
  const int total = static_cast<int>(pairs.end - pairs.first) * o.runs * o.seeds;
  ThreadPool pool(o.threads);
  int done = 0;
  std::mutex lock;
  long long first_pair = 0;
  for (std::size_t mi = 0; mi < maps.size(); ++mi) {
    const auto t_map = Clock::now();
    std::vector<std::vector<RunRecord>> records(
        kinds.size(), planned_runs(maps[mi], static_cast<int>(mi), o, first_pair, pairs));
    first_pair += sources_evaluated(maps[mi], o);
    MapReport report;
    report.name = maps[mi].name;
    report.frame = maps[mi].frame;
    if (records.front().empty()) {  // another part's map: no wind, no table
      for (EvaluationResult& r : results)
        r.maps.push_back(report);
      continue;
    }
    const std::vector<std::unique_ptr<Scenario>> scenarios = method_scenarios(maps[mi], ste);
    pool.parallel_for(records.front().size(), [&](std::size_t k) {
      run_one(scenarios, records, k, replays);
      std::lock_guard<std::mutex> g(lock);
      ++done;
      if (progress) progress(done, total);
    });
    const double wall_s = std::chrono::duration<double>(Clock::now() - t_map).count();
    add_map(report, wall_s, scenarios, records, after_map, results);
  }
  const double wall_s = std::chrono::duration<double>(Clock::now() - t_all).count();
  for (EvaluationResult& r : results) {
    r.overall = summarise(pointers(r.runs));
    r.wall_s = wall_s;
    r.threads = pool.size();
  }
  return results;
}

EvaluationResult evaluate(const std::vector<Map>& maps, const EvaluationOptions& o,
                          const std::function<void(int, int)>& progress,
                          const AfterMap& after_map) {
  AfterMethodMap each;
  if (after_map)
    each = [&](std::size_t, const Scenario& sc, const std::vector<RunRecord>& records) {
      after_map(sc, records);
    };
  return std::move(evaluate_methods(maps, o, {o.ste.method.name}, progress, each).front());
}

std::string runs_csv(const EvaluationResult& result) {
  std::ostringstream s;
  s << "map,source_index,run,source_x,source_y,start_x,start_y,estimate_x,estimate_y,error_m,"
       "samples,distance_m,mission_s,stopped_by,first_detection_s,within_1m_s,within_0_5m_s,"
       "optimum_s,over_optimum,gsl_bench"
    << (result.tracking() ? ",reached,distance_overhead" : "")
    << (result.seeds > 1 ? ",seed\n" : "\n");
  s << std::setprecision(6);
  // Positions in each map's own frame, as its file and the user's robot hold them.
  for (const RunRecord& r : result.runs) {
    const MapFrame& frame = result.maps.at(r.map_index).frame;
    const Vec2 source = frame.to_frame(r.source), start = frame.to_frame(r.start),
               estimate = frame.to_frame(r.estimate);
    run_id_columns(s, r);
    // Far from the frame's origin 6 digits would lose the millimetres.
    s << ',' << std::setprecision(frame.is_identity() ? 6 : 12) << source.x << ',' << source.y
      << ',' << start.x << ',' << start.y << ',' << estimate.x << ',' << estimate.y << ','
      << std::setprecision(6) << r.error_m << ',' << r.samples << ',' << r.distance_m << ','
      << r.mission_s << ',' << csv_field(r.stopped_by);
    // Empty where the run never got there.
    for (double v : {r.times.first_detection_s, r.times.within_1m_s, r.times.within_0_5m_s,
                     r.times.optimum_s, r.times.over_optimum()}) {
      s << ',';
      if (std::isfinite(v)) s << v;
    }
    s << ',' << (r.times.gsl_bench_success() ? 1 : 0);
    if (result.tracking()) {
      s << ',' << (r.reached ? 1 : 0) << ',';
      if (std::isfinite(r.distance_overhead)) s << r.distance_overhead;
    }
    if (result.seeds > 1) s << ',' << r.seed;
    s << '\n';
  }
  return s.str();
}

std::string timings_csv(const EvaluationResult& result) {
  std::ostringstream s;
  s << "map,source_index,run" << (result.seeds > 1 ? ",seed" : "") << ",compute_s,median_step_s\n";
  s << std::setprecision(6);
  for (const RunRecord& r : result.runs) {
    run_id_columns(s, r);
    if (result.seeds > 1) s << ',' << r.seed;
    s << ',' << r.compute_s << ',' << r.median_step_s << '\n';
  }
  return s.str();
}

}  // namespace plumekit::run
