#include "run/tunnel_run.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>

#include "core/error.hpp"
#include "core/option_check.hpp"
#include "core/random.hpp"
#include "core/statistics.hpp"
#include "core/thread_pool.hpp"
#include "methods/registry.hpp"
#include "run/method_run.hpp"
#include "run/tunnel_replay.hpp"
#include "world/random_streams.hpp"
#include "world/tunnel_world.hpp"

namespace plumekit::run {

namespace {

std::string point_text(Vec3 p) {
  return "(" + compact(p.x) + ", " + compact(p.y) + ", " + compact(p.z) + ")";
}

Box3 inner_box(const TunnelOptions& o) {
  return o.tunnel.box().inset(o.margin);
}

// The 2-D baseline flies 10 cm below the source (ch. 17, after Rahbar et al. 2017).
double cast_altitude(const TunnelOptions& o, Vec3 source) {
  return std::clamp(source.z - 0.1, o.margin, o.tunnel.height - o.margin);
}

// The method of o.method: STE's chain and a tracker's draws come from `seed`'s own streams.
std::unique_ptr<methods::LocalizationMethod3> tunnel_method(const TunnelOptions& o, Vec3 source,
                                                            std::uint64_t seed) {
  methods::TunnelMethodInputs in;
  in.tunnel = o.tunnel.box();
  in.margin = o.margin;
  in.ste = o.ste;
  in.search = o.search;
  in.search.step = o.tracker_speed * o.decision_s;
  in.search.altitude = cast_altitude(o, source);
  in.chain_seed = splitmix64(world::stream_seed(seed, world::SteStream::Mh));
  in.walk_seed = world::stream_seed(seed, world::SteStream::Method);
  return methods::find_tunnel_method(o.method).factory(in);
}

// A robot in the tunnel, for run_loop. STE stops to sample and flies straight to its goal at the
// world's speed; a tracker reads on the move at tracker_speed (its first reading: a moment at the
// start), succeeds inside the box about the source while in the plume ("found") and fails at the
// time limit.
class TunnelRobot {
 public:
  TunnelRobot(const TunnelOptions& o, Vec3 source, Vec3 start, std::uint64_t seed,
              TunnelReplayRecorder* recorder)
      : o_(o), world_(o.tunnel, source, o.world, seed), robot_(start), recorder_(recorder) {
    method_ = tunnel_method(o, source, seed);
    run_.spinup_s = world_.spinup_s();
    world_.watch(recorder);
  }

  bool sense() {
    if (!method_->reads_while_moving())
      reading_ = world_.stop(robot_);
    else if (run_.steps.empty())
      reading_ = world_.move(robot_, robot_, o_.tracker_speed);
    return true;  // a tracker's later readings come with its moves
  }

  bool decide() {
    const double cpu = thread_cpu_s();
    method_->observe({reading_.position, reading_.gas, reading_.wind, 0.0, world_.time()});
    TunnelStep step{robot_,           reading_.gas, world_.time(), run_.distance_m,
                    method_->phase(), {},           0.0,           0.0};
    if (const ste::Posterior3* post = method_->posterior()) {
      step.estimate = post->expected_source();
      step.entropy = post->entropy;
      run_.max_entropy = post->max_entropy;
    }
    if (recorder_) recorder_->belief(world_.time(), method_->posterior());
    run_.stopped_by = stop_rule();
    if (run_.stopped_by.empty()) goal_ = method_->next(robot_).goal;
    step.compute_s = thread_cpu_s() - cpu;
    run_.steps.push_back(step);
    return !run_.stopped_by.empty();
  }

  bool move() {
    if (method_->reads_while_moving())
      reading_ = world_.move(robot_, goal_, o_.tracker_speed);
    else
      world_.travel(robot_, goal_);
    run_.distance_m += norm(goal_ - robot_);
    robot_ = goal_;
    return true;
  }

  TunnelRun finish() {
    run_.estimate = method_->estimate().value_or(robot_);
    run_.mission_s = world_.time();
    return std::move(run_);
  }

 private:
  std::string stop_rule() const {
    std::string why = method_->stopped_by();
    const std::optional<double> threshold = method_->plume_threshold();
    if (!why.empty() || !threshold) return why;
    const Vec3 d = robot_ - world_.source();
    const double half = 0.5 * o_.box;
    if (std::abs(d.x) <= half && std::abs(d.y) <= half && std::abs(d.z) <= half &&
        reading_.gas >= *threshold)
      return "found";
    if (world_.time() >= o_.time_limit_s) return "time_limit";
    return "";
  }

  const TunnelOptions& o_;
  world::TunnelWorld world_;
  std::unique_ptr<methods::LocalizationMethod3> method_;
  TunnelRun run_;
  Vec3 robot_, goal_;
  world::Reading3 reading_;
  TunnelReplayRecorder* recorder_;
};

}  // namespace

std::string parse_tunnel_method(const std::string& name) {
  return methods::find_tunnel_method(name).name;
}

std::vector<std::string> parse_tunnel_methods(const std::string& text) {
  return methods::parse_tunnel_method_list(text);
}

bool is_tracker(const std::string& method) {
  return methods::find_tunnel_method(method).tracker;
}

world::WorldOptions TunnelOptions::default_world() {
  world::WorldOptions w;
  w.filament = world::tunnel_filament_options();
  return w;
}

const OptionTable<TunnelOptions>& tunnel_option_table() {
  using O = TunnelOptions;
  static const OptionTable<O> table{
      "Tunnel runs (run::TunnelOptions; its tunnel, world, STE and search apart)",
      {{"tunnel.tracker_speed", "", &O::tracker_speed, positive(10.0, "m/s"),
        "Trackers' speed, m/s", "ch. 17: 0.05 m/s"},
       {"tunnel.decision_s", "", &O::decision_s, positive(60.0, "s"),
        "Seconds between a tracker's decisions"},
       {"tunnel.time_limit_s", "--time-limit", &O::time_limit_s, positive(1e6, "s"),
        "Trackers: seconds before a run fails (thesis: 720)", "ch. 17: 720 s"},
       {"tunnel.box", "", &O::box, positive(10.0, "m"), "Side of the trackers' success box, m",
        "ch. 17: 0.2 m"},
       {"tunnel.margin",
        "",
        &O::margin,
        {},
        "Goals and starts stay this far inside the walls, m",
        "",
        "from 0 to a quarter of the tunnel's smaller side, m"},
       {"tunnel.source_x",
        "",
        &O::source_x,
        {},
        "The source's distance from the upwind wall, m",
        "",
        "from tunnel.margin to the tunnel's length less tunnel.margin, m"},
       {"tunnel.min_start_distance",
        "",
        &O::min_start_distance,
        {},
        "Random starts at least this far from the source, m",
        "",
        "from 0 to half the tunnel's length, m"},
       {"tunnel.start_downwind", "--start-downwind", &O::start_downwind, positive(1000.0, "m"),
        "Trackers: random starts this far downwind of the source, m (thesis: 10; cut to the "
        "tunnel)",
        "ch. 17: 10 m"}}};
  return table;
}

void TunnelOptions::validate() const {
  tunnel.validate();
  world::validate_tunnel_world(world);
  ste.validate();
  search.validate();
  plumekit::validate(tunnel_option_table(), *this);
  // The ranges that depend on the tunnel's size.
  const auto defaults = [](const char* name) {
    return "the default is " + default_text(tunnel_option_table().entry(name)) + " m";
  };
  const double smallest = std::min(tunnel.width, tunnel.height);
  check_non_negative("tunnel.margin", margin, 0.25 * smallest, "m", defaults("tunnel.margin"));
  check_range("tunnel.source_x", source_x, margin, tunnel.length - margin, "m",
              "ch. 5.1: 1 m from the upwind wall");
  check_non_negative("tunnel.min_start_distance", min_start_distance, 0.5 * tunnel.length, "m",
                     defaults("tunnel.min_start_distance"));
}

Vec3 TunnelRun::error() const {
  const Vec3 d = estimate - source;
  return {std::abs(d.x), std::abs(d.y), std::abs(d.z)};
}

double TunnelRun::closest_m() const {
  double best = norm(start - source);
  for (const TunnelStep& step : steps)
    best = std::min(best, norm(step.position - source));
  return best;
}

double TunnelRun::time_within(double radius) const {
  for (const TunnelStep& step : steps)
    if (norm(step.position - source) <= radius) return step.time_s;
  return -1.0;
}

double TunnelRun::median_step_s() const {
  if (is_tracker(method)) return 0.0;
  std::vector<double> s;
  for (const TunnelStep& step : steps)
    s.push_back(step.compute_s);
  return median(s);
}

void check_tunnel_point(const TunnelOptions& o, Vec3 p, const std::string& what) {
  if (!is_finite(p) || !inner_box(o).contains(p))
    throw InputError("tunnel." + what + ": " + point_text(p) + " is not inside the " +
                     compact(o.tunnel.length) + " x " + compact(o.tunnel.width) + " x " +
                     compact(o.tunnel.height) + " m tunnel at least " + compact(o.margin) +
                     " m from its walls");
}

Vec3 random_tunnel_source(const TunnelOptions& o, std::uint64_t seed) {
  std::mt19937_64 rng(world::stream_seed(seed, world::SteStream::Start));
  const Box3 in = inner_box(o);
  const double y = uniform(rng, in.lo.y, in.hi.y);
  const double z = uniform(rng, in.lo.z, in.hi.z);
  return {o.source_x, y, z};
}

Vec3 random_tunnel_start(const TunnelOptions& o, Vec3 source, std::uint64_t seed) {
  std::mt19937_64 rng(splitmix64(world::stream_seed(seed, world::SteStream::Start)));
  const Box3 in = inner_box(o);
  if (is_tracker(o.method)) {
    const double x = std::min(source.x + o.start_downwind, in.hi.x);
    const double y = uniform(rng, in.lo.y, in.hi.y);
    const double z = uniform(rng, in.lo.z, in.hi.z);
    return {x, y, methods::find_tunnel_method(o.method).flies_flat ? cast_altitude(o, source) : z};
  }
  for (int attempt = 0; attempt < 10000; ++attempt) {
    const Vec3 p{uniform(rng, in.lo.x, in.hi.x), uniform(rng, in.lo.y, in.hi.y),
                 uniform(rng, in.lo.z, in.hi.z)};
    if (norm(p - source) >= o.min_start_distance) return p;
  }
  throw InputError("tunnel: no start at least " + compact(o.min_start_distance) +
                   " m from the source " + point_text(source));
}

TunnelRun run_tunnel(const TunnelOptions& o, Vec3 source, Vec3 start, std::uint64_t seed,
                     TunnelReplayRecorder* recorder) {
  o.validate();
  check_tunnel_point(o, source, "source");
  check_tunnel_point(o, start, "start");
  TunnelRobot robot(o, source, start, seed, recorder);
  run_loop(robot);
  TunnelRun run = robot.finish();
  run.method = o.method;
  run.source = source;
  run.start = start;
  return run;
}

TunnelRun localize_tunnel(const TunnelOptions& o, std::optional<Vec3> source,
                          std::optional<Vec3> start, std::uint64_t seed, std::uint64_t run,
                          std::optional<Replay>* replay) {
  const std::uint64_t s = world::run_seed(seed, 0, 0, run);
  if (!source) source = random_tunnel_source(o, s);
  check_tunnel_point(o, *source, "source");  // before a start is drawn about it
  if (!start) start = random_tunnel_start(o, *source, s);
  if (!replay) return run_tunnel(o, *source, *start, s);
  TunnelReplayRecorder recorder = tunnel_replay_recorder(o, *source);
  TunnelRun r = run_tunnel(o, *source, *start, s, &recorder);
  *replay = recorder.finish(r, tunnel_replay_title(o, r.source, seed));
  return r;
}

std::vector<TunnelRun> evaluate_tunnel(const TunnelOptions& o, int runs, std::uint64_t seed,
                                       int threads, const std::function<void(int, int)>& progress,
                                       const TunnelReplaySink& replayed) {
  o.validate();
  check_count("tunnel.runs", runs, 1, 100'000, "the default is 10");
  std::vector<TunnelRun> out(runs);
  ThreadPool pool(threads);
  std::mutex mutex;
  int done = 0;
  pool.parallel_for(runs, [&](std::size_t k) {
    std::optional<Replay> replay;
    out[k] = localize_tunnel(o, std::nullopt, std::nullopt, seed, k, replayed ? &replay : nullptr);
    if (replay) {
      replay->title += ", run " + std::to_string(k);
      replayed(static_cast<int>(k), out[k], *replay);
    }
    std::lock_guard<std::mutex> lock(mutex);
    if (progress) progress(++done, runs);
  });
  return out;
}

}  // namespace plumekit::run
