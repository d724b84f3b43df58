#include "run/method_run.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>

#include "core/error.hpp"
#include "core/statistics.hpp"
#include "run/replay_recorder.hpp"

namespace plumekit::run {

double thread_cpu_s() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

double wall_clock_s() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

namespace {

// The straight way from the robot towards `goal` (in the arena), up to where it would first
// leave the free space at the planner's margin: where an obstacle's avoidance stops the robot.
// `blocked` says whether it stopped short.
planner::PlanResult straight_to(Vec2 goal, Vec2 robot, const planner::FreeSpace& space,
                                bool& blocked) {
  const Map& map = space.map();
  goal = {std::clamp(goal.x, 0.0, map.width), std::clamp(goal.y, 0.0, map.height)};
  const double length = norm(goal - robot);
  const int steps = static_cast<int>(std::ceil(length / 0.01));
  Vec2 end = robot;
  blocked = false;
  for (int k = 1; k <= steps; ++k) {
    const Vec2 q = robot + (static_cast<double>(k) / steps) * (goal - robot);
    if (!space.contains(q)) {
      blocked = true;
      break;
    }
    end = q;
  }
  planner::PlanResult p;
  p.path = {robot, end};
  p.length = norm(end - robot);
  p.goal = end;
  return p;
}

// The path to a method's goal: its own, the straight way of a method without a map, or the
// planner's to the goal moved into the arena and off the obstacles (by the planner's margin). An
// unreachable goal gives a path of length 0.
planner::PlanResult path_to(const methods::Move& move, Vec2 robot, const planner::Planner& planner,
                            const MethodRunOptions& o, bool& blocked) {
  blocked = false;
  if (move.straight) {
    if (o.space == nullptr)
      throw std::logic_error("run_method: a method that drives straight needs the free space");
    return straight_to(move.goal, robot, *o.space, blocked);
  }
  planner::PlanResult p;
  if (!move.path.empty()) {
    p.path = move.path;
    p.length = move.length;
    p.goal = move.goal;
    return p;
  }
  if (o.space == nullptr)
    throw std::logic_error("run_method: a method without its own paths needs the free space");
  const Map& map = o.space->map();
  Vec2 goal{std::clamp(move.goal.x, 0.0, map.width), std::clamp(move.goal.y, 0.0, map.height)};
  if (!o.space->contains(goal)) goal = o.space->nearest_free(goal);
  if (o.space->region_of(goal) != o.space->region_of(o.space->nearest_free(robot))) goal = robot;
  if (norm(goal - robot) < 1e-9) {
    p.path = {robot, robot};
    p.goal = robot;
    return p;
  }
  return planner.plan(robot, goal);
}

}  // namespace

std::optional<SourceDisc::Entry> SourceDisc::entry(const std::vector<Vec2>& path) const {
  double walked = 0.0;
  for (std::size_t k = 1; k < path.size(); ++k) {
    const Vec2 a = path[k - 1], d = path[k] - a;
    const double leg = norm(d);
    // The smallest t in [0, 1] with |a + t d - source| <= radius.
    const Vec2 f = a - source;
    const double qa = dot(d, d), qb = 2.0 * dot(f, d), qc = dot(f, f) - radius * radius;
    double t = -1.0;
    if (qc <= 0.0) {
      t = 0.0;
    } else if (qa > 0.0) {
      const double disc2 = qb * qb - 4.0 * qa * qc;
      if (disc2 >= 0.0) {
        const double t0 = (-qb - std::sqrt(disc2)) / (2.0 * qa);
        if (t0 >= 0.0 && t0 <= 1.0) t = t0;
      }
    }
    if (t >= 0.0) return Entry{k, t, walked + t * leg};
    walked += leg;
  }
  return std::nullopt;
}

void cut_at_entry(const SourceDisc& disc, planner::PlanResult& path) {
  const std::optional<SourceDisc::Entry> e = disc.entry(path.path);
  if (!e) return;
  const Vec2 a = path.path[e->leg - 1], entry = a + e->t * (path.path[e->leg] - a);
  path.path.resize(e->leg);
  path.path.push_back(entry);
  path.length = e->along;
  path.goal = entry;
}

std::vector<PassingRecord> passing_records(const std::vector<world::TransitReading>& readings,
                                           double t_start) {
  std::vector<PassingRecord> out;
  out.reserve(readings.size());
  for (const world::TransitReading& r : readings)
    out.push_back({r.position, r.recorded, r.time_s - t_start, r.value});
  return out;
}

std::vector<methods::BasicPassing<Vec2>> passing_observations(
    const std::vector<PassingRecord>& records) {
  std::vector<methods::BasicPassing<Vec2>> out;
  out.reserve(records.size());
  for (const PassingRecord& r : records)
    out.push_back({r.recorded, r.time_s, r.value});
  return out;
}

namespace {

// The method's state after a stop, into the step's record (a method with a posterior adds its).
void record_state(const methods::LocalizationMethod& method, Step& s, LocalizationResult& r) {
  if (const ste::Posterior* posterior = method.posterior()) {
    r.posterior = *posterior;
    s.estimate = r.posterior.expected_source();
    s.map = r.posterior.map;
    s.entropy = r.posterior.entropy;
    return;
  }
  s.estimate = method.estimate().value_or(s.position);
  s.map = s.estimate;
}

}  // namespace

bool SourceBox::contains(Vec2 p) const {
  const Vec2 d = p - source;
  const double a = dot(d, downwind), c = cross(downwind, d);
  return a >= 0.0 && a <= along && std::abs(c) <= 0.5 * across;
}

namespace {

// A robot alone on a floor, for run_loop: a whole stop, decision or move per call.
class FloorRobot {
 public:
  FloorRobot(Vec2 start, methods::LocalizationMethod& method, world::SimulatedWorld& world,
             const planner::Planner& planner, const MethodRunOptions& options)
      : method_(method), world_(world), planner_(planner), options_(options), pos_(start) {
    r_.method = method.name();
    r_.start = start;
    t_start_ = world.time();
    if (options.recorder != nullptr) world.watch(options.recorder, start);
  }

  bool sense() {
    step_ = Step{};
    step_.position = pos_;
    step_.distance_m = r_.distance_m;
    step_.path_in = std::move(path_in_);
    step_.on_the_way = passing_records(world_.take_transit_readings(), t_start_);
    step_.arrived_s = world_.time() - t_start_;
    reading_ = world_.stop(pos_);
    step_.value = reading_.gas;
    step_.wind = reading_.wind;
    step_.recorded = reading_.position;
    step_.time_s = world_.time() - t_start_;
    return true;
  }

  bool decide() {
    const double t0 = thread_cpu_s(), w0 = wall_clock_s();
    method_.observe({reading_.position, reading_.gas, reading_.wind, reading_.wind_variance,
                     step_.time_s, blocked_, passing_observations(step_.on_the_way)});
    record_state(method_, step_, r_);
    if (options_.recorder != nullptr) options_.recorder->belief(0, step_.time_s, method_);
    r_.stopped_by = stop_reason(method_, pos_, static_cast<int>(r_.steps.size()) + 1, options_);
    path_ = {};
    if (r_.stopped_by.empty())
      path_ = path_to(method_.next(pos_), pos_, planner_, options_, blocked_);
    if (r_.stopped_by.empty() && options_.disc) cut_at_entry(*options_.disc, path_);
    step_.compute_s = thread_cpu_s() - t0;
    r_.decisions_s += wall_clock_s() - w0;
    step_times_.push_back(step_.compute_s);
    r_.compute_s += step_.compute_s;
    r_.steps.push_back(std::move(step_));
    ++r_.samples;
    return !r_.stopped_by.empty();
  }

  bool move() {
    world_.travel(path_.path, path_.length);
    r_.distance_m += path_.length;
    pos_ = path_.goal;
    path_in_ = std::move(path_.path);
    return true;
  }

  // The drive to the estimate after the method stopped (MethodRunOptions::approach).
  void approach() {
    const std::optional<Vec2> estimate = method_.estimate();
    if (!options_.approach || r_.stopped_by == "reached" || !estimate) return;
    bool blocked = false;
    const planner::PlanResult p =
        path_to(methods::Move::to(*estimate), pos_, planner_, options_, blocked);
    if (p.length <= 0.0) return;
    const double t0 = world_.time();
    world_.travel(p.path, p.length);
    world_.take_transit_readings();  // read on the way, but nobody decides on them any more
    r_.distance_m += p.length;
    r_.approach = p.path;
    r_.approach_s = world_.time() - t0;
    pos_ = p.goal;
  }

  LocalizationResult finish() {
    approach();
    if (options_.recorder != nullptr) world_.watch(nullptr, pos_);
    r_.reached = r_.stopped_by == "reached";
    if (std::optional<Grid<double>> belief = method_.belief_map(world_.map()))
      r_.posterior.marginal = std::move(*belief);
    r_.expected = r_.posterior.expected;
    r_.estimate = method_.estimate().value_or(pos_);
    r_.map = r_.steps.back().map;
    r_.time_s = world_.time() - t_start_;
    r_.median_step_s = median(step_times_);
    return std::move(r_);
  }

 private:
  methods::LocalizationMethod& method_;
  world::SimulatedWorld& world_;
  const planner::Planner& planner_;
  const MethodRunOptions& options_;
  LocalizationResult r_;
  double t_start_ = 0.0;
  Vec2 pos_;
  world::Reading reading_;
  Step step_;
  planner::PlanResult path_;
  std::vector<Vec2> path_in_;
  bool blocked_ = false;  // the last move stopped short at an obstacle
  std::vector<double> step_times_;
};

}  // namespace

std::string stop_reason(const methods::LocalizationMethod& method, Vec2 pos, int stops,
                        const MethodRunOptions& options) {
  std::string why = method.stopped_by();
  if (why.empty() && options.box && options.box->contains(pos)) why = "reached";
  if (why.empty() && options.disc && options.disc->contains(pos)) why = "reached";
  if (why.empty() && stops >= options.max_stops) why = "max_samples";
  return why;
}

LocalizationResult run_method(Vec2 start, methods::LocalizationMethod& method,
                              world::SimulatedWorld& world, const planner::Planner& planner,
                              const MethodRunOptions& options) {
  FloorRobot robot(start, method, world, planner, options);
  run_loop(robot);
  return robot.finish();
}

}  // namespace plumekit::run
