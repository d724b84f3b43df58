#include "ste/localizer.hpp"

#include <ctime>

#include "core/error.hpp"
#include "core/statistics.hpp"
#include "ste/mission.hpp"

namespace plumekit::ste {

namespace {

// CPU time of the calling thread: a decision step runs on one thread, and
// this reads the same on a loaded machine as on a quiet one.
double thread_cpu_s() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

}  // namespace

std::string stop_reason(const Posterior& posterior, int samples, const StopOptions& stop) {
  if (posterior.entropy < stop.entropy_fraction * posterior.max_entropy &&
      posterior.seen_mass >= stop.seen_mass)
    return "entropy";
  return samples >= stop.max_samples_in_use() ? "max_samples" : "";
}

LocalizationResult localize(Vec2 start, Estimator& estimator, SimulatedWorld& world,
                            const planner::Planner& planner, const Navigator& navigator,
                            const StopOptions& stop) {
  Mission mission(estimator, planner, navigator, stop);
  LocalizationResult r;
  r.start = start;
  const double t_start = world.time();
  Vec2 pos = start;
  std::vector<Vec2> path_in;
  std::vector<double> step_times;
  for (;;) {
    Step s;
    s.position = pos;
    s.distance_m = r.distance_m;
    s.path_in = std::move(path_in);
    const Reading reading = world.stop(pos);
    s.value = reading.gas;
    s.wind = reading.wind;
    s.recorded = reading.position;
    s.time_s = world.time() - t_start;

    const double t0 = thread_cpu_s();
    r.posterior = mission.add(reading.position, s.value);
    s.estimate = r.posterior.expected_source();
    s.map = r.posterior.map;
    s.entropy = r.posterior.entropy;
    r.stopped_by = mission.stopped_by();
    planner::PlanResult path;
    if (!mission.stopped()) path = mission.next(pos);
    s.compute_s = thread_cpu_s() - t0;
    step_times.push_back(s.compute_s);
    r.compute_s += s.compute_s;
    r.steps.push_back(std::move(s));
    if (mission.stopped()) break;

    world.travel(path.path, path.length);
    r.distance_m += path.length;
    pos = path.goal;
    path_in = std::move(path.path);
  }
  r.samples = estimator.samples();
  r.expected = r.posterior.expected;
  r.estimate = r.posterior.expected_source();
  r.map = r.posterior.map;
  r.time_s = world.time() - t_start;
  r.median_step_s = median(step_times);
  return r;
}

}  // namespace plumekit::ste
