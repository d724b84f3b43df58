#include "ste/evaluation.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <iomanip>
#include <mutex>
#include <sstream>
#include <thread>

#include "core/error.hpp"

namespace plumekit::ste {

namespace {

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace

Stats summarise(const std::vector<const RunRecord*>& runs) {
  Stats s;
  s.runs = static_cast<int>(runs.size());
  if (runs.empty()) return s;
  std::vector<double> err, samples, dist, step;
  double sum = 0;
  for (const RunRecord* r : runs) {
    err.push_back(r->error_m);
    samples.push_back(r->samples);
    dist.push_back(r->distance_m);
    step.push_back(r->median_step_s);
    sum += r->error_m;
    s.success_0_5 += r->error_m <= 0.5;
    s.success_1_0 += r->error_m <= 1.0;
    s.entropy_stops += r->stopped_by == "entropy";
  }
  const double n = static_cast<double>(runs.size());
  s.median_error_m = median(err);
  s.mean_error_m = sum / n;
  s.success_0_5 /= n;
  s.success_1_0 /= n;
  s.entropy_stops /= n;
  s.median_samples = median(samples);
  s.median_distance_m = median(dist);
  s.median_step_s = median(step);
  return s;
}

EvaluationResult evaluate(const std::vector<Map>& maps, const EvaluationOptions& o,
                          const std::function<void(int, int)>& progress,
                          const AfterMap& after_map) {
  o.validate();
  using Clock = std::chrono::steady_clock;
  const auto t_all = Clock::now();
  EvaluationResult result;
  int total = 0;
  for (const Map& m : maps) {
    if (m.sources.empty())
      throw InputError("map " + m.name + " has no ground-truth \"sources\" to evaluate on");
    const int k = o.sources > 0 ? std::min<int>(o.sources, m.sources.size()) : m.sources.size();
    total += k * o.runs;
  }
  int done = 0;
  std::mutex lock;
  for (std::size_t mi = 0; mi < maps.size(); ++mi) {
    const Map& map = maps[mi];
    const auto t_map = Clock::now();
    const Scenario scenario(map, o.ste);
    const int n_src =
        o.sources > 0 ? std::min<int>(o.sources, map.sources.size()) : map.sources.size();
    std::vector<RunRecord> records(static_cast<std::size_t>(n_src) * o.runs);
    for (int s = 0; s < n_src; ++s)
      for (int r = 0; r < o.runs; ++r) {
        RunRecord& rec = records[static_cast<std::size_t>(s) * o.runs + r];
        rec.map = map.name;
        rec.map_index = static_cast<int>(mi);
        rec.source_index = s;
        rec.run = r;
        rec.source = map.sources[s];
      }
    std::atomic<std::size_t> next{0};
    std::exception_ptr failure;
    auto worker = [&] {
      for (;;) {
        const std::size_t k = next++;
        if (k >= records.size()) return;
        RunRecord& rec = records[k];
        try {
          const std::uint64_t seed = run_seed(o.seed, mi, rec.source_index, rec.run);
          rec.start = scenario.random_start(rec.source, seed ^ 0xA5A5);
          rec.result = scenario.run(rec.source, rec.start, seed);
        } catch (...) {
          std::lock_guard<std::mutex> g(lock);
          if (!failure) failure = std::current_exception();
          next = records.size();
          return;
        }
        const LocalizationResult& r = rec.result;
        rec.estimate = r.estimate;
        rec.error_m = norm(r.estimate - rec.source);
        rec.samples = r.samples;
        rec.distance_m = r.distance_m;
        rec.mission_s = r.time_s;
        rec.compute_s = r.compute_s;
        rec.median_step_s = r.median_step_s;
        rec.stopped_by = r.stopped_by;
        std::lock_guard<std::mutex> g(lock);
        ++done;
        if (progress) progress(done, total);
      }
    };
    std::vector<std::thread> pool;
    for (int t = 0; t < o.threads; ++t)
      pool.emplace_back(worker);
    for (std::thread& t : pool)
      t.join();
    if (failure) std::rethrow_exception(failure);

    MapReport report;
    report.name = map.name;
    report.wind_s = scenario.wind_seconds();
    report.table_build_s = scenario.model_seconds();
    std::vector<const RunRecord*> ptrs;
    for (const RunRecord& r : records)
      ptrs.push_back(&r);
    report.stats = summarise(ptrs);
    report.wall_s = std::chrono::duration<double>(Clock::now() - t_map).count();
    result.maps.push_back(report);
    if (after_map) after_map(scenario, records);
    for (RunRecord& r : records)
      result.runs.push_back(std::move(r));
  }
  std::vector<const RunRecord*> all;
  for (const RunRecord& r : result.runs)
    all.push_back(&r);
  result.overall = summarise(all);
  result.wall_s = std::chrono::duration<double>(Clock::now() - t_all).count();
  return result;
}

std::string runs_csv(const EvaluationResult& result) {
  std::ostringstream s;
  s << "map,source_index,run,source_x,source_y,start_x,start_y,estimate_x,estimate_y,error_m,"
       "samples,distance_m,mission_s,compute_s,median_step_s,stopped_by\n";
  s << std::setprecision(6);
  for (const RunRecord& r : result.runs)
    s << r.map << ',' << r.source_index << ',' << r.run << ',' << r.source.x << ',' << r.source.y
      << ',' << r.start.x << ',' << r.start.y << ',' << r.estimate.x << ',' << r.estimate.y << ','
      << r.error_m << ',' << r.samples << ',' << r.distance_m << ',' << r.mission_s << ','
      << r.compute_s << ',' << r.median_step_s << ',' << r.stopped_by << '\n';
  return s.str();
}

}  // namespace plumekit::ste
