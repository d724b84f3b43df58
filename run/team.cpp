#include "run/team.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "core/error.hpp"
#include "core/statistics.hpp"
#include "methods/method.hpp"
#include "run/replay_recorder.hpp"
#include "world/random_streams.hpp"

namespace plumekit::run {

const char* to_string(TeamStrategy strategy) {
  switch (strategy) {
    case TeamStrategy::Individualist:
      return "individualist";
    case TeamStrategy::Cooperative:
      return "cooperative";
    case TeamStrategy::Collaborative:
      return "collaborative";
  }
  return "?";
}

TeamStrategy parse_team_strategy(const std::string& name) {
  for (TeamStrategy s :
       {TeamStrategy::Individualist, TeamStrategy::Cooperative, TeamStrategy::Collaborative})
    if (name == to_string(s)) return s;
  throw OptionError(
      "ste.team.strategy",
      "\"" + name + "\" is not a strategy (individualist, cooperative, collaborative)");
}

bool may_move(Vec2 from, Vec2 to, Vec2 other, double separation) {
  const double after = norm(to - other);
  return after >= separation || after >= norm(from - other);
}

std::optional<Vec2> free_goal(Vec2 goal, const std::vector<Vec2>& taken, double separation,
                              const std::function<bool(Vec2)>& usable) {
  const auto clear = [&](Vec2 g) {
    for (Vec2 t : taken)
      if (norm(g - t) < separation) return false;
    return true;
  };
  if (clear(goal)) return goal;
  for (int ring = 1; ring <= 8; ++ring)
    for (int k = 0; k < 12; ++k) {
      const double a = 2.0 * kPi * k / 12.0, r = 0.5 * separation * ring;
      const Vec2 g{goal.x + r * std::cos(a), goal.y + r * std::sin(a)};
      if (clear(g) && usable(g)) return g;
    }
  return std::nullopt;
}

int best_swap(const Heading& robot, const std::vector<Heading>& moving,
              const std::function<double(Vec2, Vec2)>& distance, double min_gain) {
  int best = -1;
  double best_gain = min_gain;
  const double own = distance(robot.position, robot.goal);
  for (std::size_t j = 0; j < moving.size(); ++j) {
    const Heading& m = moving[j];
    const double now = own + distance(m.position, m.goal);
    const double swapped = distance(robot.position, m.goal) + distance(m.position, robot.goal);
    if (std::isfinite(swapped) && now - swapped > best_gain) {
      best_gain = now - swapped;
      best = static_cast<int>(j);
    }
  }
  return best;
}

namespace {

struct Robot {
  int index = 0;
  std::unique_ptr<world::SimulatedWorld> world;
  methods::LocalizationMethod* method = nullptr;
  methods::Teammate* mate = nullptr;  // the same method, as a team member
  Phase phase = Phase::Sense;         // where it is in the run loop (method_run.hpp)
  Vec2 pos;
  bool stopping = false;               // its stop's readings have begun
  double arrived_s = 0.0;              // when it arrived at the stop, since the team started
  std::vector<PassingRecord> passing;  // its readings on the way there
  world::Reading reading;              // the stop just ended (to decide on)
  // Moving: the path, its duration and whole reading intervals, those moved so far, metres done.
  planner::PlanResult path;
  double seconds = 0.0;
  int ticks = 0, tick = 0;
  double along = 0.0;
  std::vector<Vec2> travelled;  // covered since the last stop (paths cut short by swaps included)
  bool halted = false;          // its last action was a wait
  double obstructed = 0.0;      // s of this travel spent waiting or stepping aside
  std::vector<methods::Teammate::Sample> inbox;  // teammates' samples not yet shared
  TeamRobot out;
  std::vector<double> step_times;
  double compute_s = 0.0, decisions_s = 0.0;
};

class TeamRun {
 public:
  TeamRun(world::SharedPlume& plume, const std::vector<Vec2>& starts,
          const std::vector<methods::LocalizationMethod*>& members, std::uint64_t seed,
          const TeamSetup& setup, const TeamOptions& team, const MethodRunOptions& options)
      : plume_(plume), setup_(setup), team_(team), options_(options) {
    if (starts.empty() || starts.size() != members.size() ||
        static_cast<int>(starts.size()) != plume.robots())
      throw std::logic_error("run_team: one start, method and plume robot per robot");
    for (std::size_t k = 0; k < starts.size(); ++k) {
      Robot r;
      r.index = static_cast<int>(k);
      r.world = std::make_unique<world::SimulatedWorld>(plume, r.index, *setup.map, setup.source,
                                                        *setup.world,
                                                        world::team_robot_seed(seed, r.index));
      r.method = members[k];
      r.mate = r.method->as_teammate();
      if (r.mate == nullptr)
        throw std::logic_error("run_team: " + r.method->name() + " cannot work in a team");
      r.pos = starts[k];
      r.out.start = starts[k];
      robots_.push_back(std::move(r));
    }
    t_start_ = robots_.front().world->time();
    if (options_.recorder != nullptr) {
      plume_.watch(options_.recorder);
      for (Robot& r : robots_)
        r.world->watch(options_.recorder, r.pos);
    }
  }

  LocalizationResult run() {
    while (!over_) {
      // The robot whose next action reads the plume earliest acts; a tie goes to the lower index.
      Robot* next = nullptr;
      for (Robot& r : robots_)
        if (r.phase != Phase::Done && (next == nullptr || read_step(r) < read_step(*next)))
          next = &r;
      if (next == nullptr) break;
      act(*next);
      if (next->phase != Phase::Done) plume_.promise(next->index, read_step(*next));
      for (Robot& o : robots_)
        if (o.index != next->index && o.phase != Phase::Done) {
          const double d = norm(o.pos - next->pos);
          next->out.closest_m = std::min(next->out.closest_m, d);
          o.out.closest_m = std::min(o.out.closest_m, d);
        }
    }
    return result();
  }

 private:
  // The plume step the robot's next action reads at: now, or for a sensor with memory on the
  // way, at the end of the reading interval (SimulatedWorld::pass). The plume is promised it, so
  // that no robot waits for another on this one thread.
  static long long read_step(const Robot& r) {
    if (r.phase == Phase::Move && r.tick < r.ticks && r.world->reads_while_travelling())
      return r.world->steps_after(r.world->reading_interval());
    return r.world->steps();
  }

  // A robot of the team in the run loop (method_run.hpp's act): a reading of its stop, its
  // decision, or a reading interval of its move per action.
  struct Member {
    TeamRun& team;
    Robot& r;
    bool sense() { return team.sense(r); }
    bool decide() { return team.decide(r); }
    bool move() { return team.travel(r); }
  };

  void act(Robot& r) {
    Member member{*this, r};
    r.phase = run::act(member, r.phase);
  }

  // One reading of the robot's stop; true once the stop is over.
  bool sense(Robot& r) {
    if (!r.stopping) {
      r.world->begin_stop(r.pos);
      r.stopping = true;
      r.arrived_s = r.world->time() - t_start_;
      r.passing = passing_records(r.world->take_transit_readings(), t_start_);
    }
    if (!r.world->stop_reading()) return false;
    r.reading = r.world->end_stop();
    r.stopping = false;
    return true;
  }

  // The stop's sample (and the teammates' since the last), the stop rules, the next goal; true
  // when the robot's run (or the team's) ends here.
  bool decide(Robot& r) {
    const double t0 = thread_cpu_s(), w0 = wall_clock_s();
    Step s;
    s.position = r.pos;
    s.recorded = r.reading.position;
    s.value = r.reading.gas;
    s.wind = r.reading.wind;
    s.time_s = r.world->time() - t_start_;
    s.arrived_s = r.arrived_s;
    s.on_the_way = std::move(r.passing);
    r.passing.clear();
    s.distance_m = r.out.distance_m;
    s.path_in = std::move(r.travelled);
    r.travelled.clear();
    if (team_.shares_samples()) {
      r.mate->share(r.inbox);
      r.inbox.clear();
    }
    r.method->observe({r.reading.position, r.reading.gas, r.reading.wind, r.reading.wind_variance,
                       s.time_s, false, passing_observations(s.on_the_way)});
    if (team_.shares_samples()) {
      // Its readings on the way as it took them in, then the stop's sample.
      std::vector<methods::Teammate::Sample> sent = r.mate->passing_samples();
      sent.push_back({r.reading.position, r.reading.gas});
      for (Robot& o : robots_)
        if (o.index != r.index && o.phase != Phase::Done)
          o.inbox.insert(o.inbox.end(), sent.begin(), sent.end());
    }
    if (options_.recorder != nullptr) options_.recorder->belief(r.index, s.time_s, *r.method);
    const ste::Posterior& post = posterior(r);
    s.estimate = post.expected_source();
    s.map = post.map;
    s.entropy = post.entropy;

    const std::string stopped =
        stop_reason(*r.method, r.pos, static_cast<int>(r.out.steps.size()) + 1, options_);
    // A declaration (either stop rule of STE's) or the source reached ends the team's mission;
    // a robot out of budget only leaves.
    if (stopped == "entropy" || stopped == "confident" || stopped == "reached") {
      over_ = true;
      declared_by_ = r.index;
      stopped_by_ = stopped;
      r.out.stopped_by = stopped;
    } else if (!stopped.empty()) {
      r.out.stopped_by = stopped;
      plume_.leave(r.index);
    } else {
      plan(r);
    }
    s.compute_s = thread_cpu_s() - t0;
    r.decisions_s += wall_clock_s() - w0;
    r.step_times.push_back(s.compute_s);
    r.compute_s += s.compute_s;
    r.out.steps.push_back(std::move(s));
    return !stopped.empty();
  }

  // A team's methods hold a posterior (traits.teams).
  static const ste::Posterior& posterior(const Robot& r) {
    const ste::Posterior* p = r.method->posterior();
    if (p == nullptr) throw std::logic_error("run_team: " + r.method->name() + " has no posterior");
    return *p;
  }

  // Where a teammate is headed: its goal while it travels, else where it stands.
  static Vec2 heading_of(const Robot& o) { return o.phase == Phase::Move ? o.path.goal : o.pos; }

  void plan(Robot& r) {
    std::vector<Vec2> virtual_points;
    if (team_.coordinates())
      for (const Robot& o : robots_)
        if (o.index != r.index && o.phase != Phase::Done) virtual_points.push_back(heading_of(o));
    const methods::Move move = r.mate->next_beside(r.pos, virtual_points);
    planner::PlanResult p;
    p.path = move.path;
    p.length = move.length;
    p.goal = move.goal;
    keep_apart(r, p);
    if (team_.coordinates()) {
      std::vector<Heading> moving;
      std::vector<Robot*> who;
      for (Robot& o : robots_)
        if (o.index != r.index && o.phase == Phase::Move) {
          moving.push_back({o.pos, o.path.goal});
          who.push_back(&o);
        }
      const auto distance = [this](Vec2 a, Vec2 b) {
        try {
          return setup_.planner->plan(a, b).length;
        } catch (const InputError&) {
          return std::numeric_limits<double>::infinity();
        }
      };
      const int j = best_swap({r.pos, p.goal}, moving, distance);
      if (j >= 0) {
        Robot& o = *who[static_cast<std::size_t>(j)];
        const Vec2 mine = p.goal, theirs = o.path.goal;
        planner::PlanResult onward = setup_.planner->plan(o.pos, mine);
        if (options_.disc) cut_at_entry(*options_.disc, onward);
        // The teammate promised the plume a reading on its way (read_step); a way shorter than
        // one reading interval has none, so it keeps its goal then (a swap that saves nothing).
        const double interval = o.world->reading_interval();
        const bool keeps_promise =
            read_step(o) == o.world->steps() || onward.length / setup_.world->speed >= interval;
        if (keeps_promise) {
          p = setup_.planner->plan(r.pos, theirs);
          leave_path(o);  // what it covered of its old path counts
          start_travel(o, std::move(onward));
          ++o.out.swaps;
          ++r.out.swaps;
        }
      }
    }
    start_travel(r, std::move(p));
  }

  // A goal where a teammate stands or is headed moves to the nearest free point that is not
  // (free_goal): robots that read alike choose alike, and would otherwise stop one another.
  void keep_apart(const Robot& r, planner::PlanResult& p) const {
    if (team_.separation <= 0.0) return;
    std::vector<Vec2> taken;
    for (const Robot& o : robots_)
      if (o.index != r.index && o.phase != Phase::Done) {
        taken.push_back(o.pos);
        if (o.phase == Phase::Move) taken.push_back(o.path.goal);
      }
    const int region = setup_.space->region_of(setup_.space->nearest_free(r.pos));
    const auto usable = [&](Vec2 g) {
      return setup_.map->in_arena(g) && setup_.space->contains(g) &&
             setup_.space->region_of(g) == region;
    };
    const std::optional<Vec2> goal = free_goal(p.goal, taken, team_.separation, usable);
    if (goal && norm(*goal - p.goal) > 0.0) p = setup_.planner->plan(r.pos, *goal);
  }

  void start_travel(Robot& r, planner::PlanResult p) {
    if (options_.disc) cut_at_entry(*options_.disc, p);
    r.path = std::move(p);
    r.seconds = r.path.length / setup_.world->speed;
    r.ticks = static_cast<int>(std::floor(r.seconds / r.world->reading_interval()));
    r.tick = 0;
    r.along = 0.0;
    r.halted = false;
    r.obstructed = 0.0;
  }

  // The robot leaves its path where it is: the part covered is travelled.
  void leave_path(Robot& r) {
    append(r.travelled, path_prefix(r.path.path, r.along));
    r.out.distance_m += r.along;
  }

  static void append(std::vector<Vec2>& to, const std::vector<Vec2>& more) {
    for (std::size_t k = 0; k < more.size(); ++k)
      if (k > 0 || to.empty() || to.back() != more[k]) to.push_back(more[k]);
  }

  // What keeps `r` from moving to q: nothing, a teammate that would come closer than the
  // separation, or one standing (sampling, deciding, waiting) within the separation of r's goal,
  // which r cannot reach then.
  enum class Block { None, Wait, GoalTaken };
  Block blocked(const Robot& r, Vec2 q) const {
    Block b = Block::None;
    for (const Robot& o : robots_) {
      if (o.index == r.index || o.phase == Phase::Done ||
          may_move(r.pos, q, o.pos, team_.separation))
        continue;
      const bool standing = o.phase != Phase::Move || o.halted;
      if (standing && norm(o.pos - r.path.goal) < team_.separation) return Block::GoalTaken;
      b = Block::Wait;
    }
    return b;
  }

  // Steps aside, 45 or else 90 degrees off its way to q, turning away from the nearest teammate,
  // where that keeps the separation, and replans to its goal from there: robots pass each other
  // as the thesis's Kheperas did by their obstacle avoidance. False when no side step is free.
  bool sidestep(Robot& r, Vec2 q, bool last) {
    const double interval = r.world->reading_interval(), step = interval * setup_.world->speed;
    const Vec2 way = q - r.pos;
    if (norm(way) < 1e-12) return false;
    const Vec2 d = (1.0 / norm(way)) * way;
    const Robot* nearest = nullptr;
    for (const Robot& o : robots_)
      if (o.index != r.index && o.phase != Phase::Done &&
          (nearest == nullptr || norm(o.pos - q) < norm(nearest->pos - q)))
        nearest = &o;
    const double away = nearest != nullptr && cross(d, nearest->pos - r.pos) > 0.0 ? -1.0 : 1.0;
    const int region = setup_.space->region_of(setup_.space->nearest_free(r.pos));
    for (double degrees : {45.0, 90.0}) {
      const double a = away * degrees * kPi / 180.0;
      const Vec2 c = r.pos + step * Vec2{std::cos(a) * d.x - std::sin(a) * d.y,
                                         std::sin(a) * d.x + std::cos(a) * d.y};
      if (!setup_.map->in_arena(c) || !setup_.space->contains(c) ||
          setup_.space->region_of(c) != region)
        continue;
      bool apart = true;
      for (const Robot& o : robots_)
        apart = apart && (o.index == r.index || o.phase == Phase::Done ||
                          may_move(r.pos, c, o.pos, team_.separation));
      if (!apart) continue;
      planner::PlanResult onward;
      try {
        onward = setup_.planner->plan(c, r.path.goal);
      } catch (const InputError&) {
        continue;
      }
      // The interval it steps in; a sensor with memory reads at its end as promised (read_step).
      if (last)
        r.world->wait(interval);
      else
        r.world->pass({c}, 0.0);
      leave_path(r);
      append(r.travelled, {c});
      r.out.distance_m += norm(c - r.pos);
      r.pos = c;
      const double obstructed = r.obstructed;
      start_travel(r, std::move(onward));
      r.obstructed = obstructed;
      return true;
    }
    return false;
  }

  // One reading interval of travel, or the last part of one; or a wait or a side step. True
  // once the move is over (arrived, or given up to sample where it is).
  bool travel(Robot& r) {
    const double interval = r.world->reading_interval();
    const bool last = r.tick >= r.ticks;
    const double to = last ? r.path.length : (r.tick + 1) * interval * setup_.world->speed;
    const Vec2 q = last ? r.path.goal : point_along(r.path.path, to);
    const Block block = blocked(r, q);
    if (block == Block::GoalTaken) {  // as close as it gets: samples here
      // The interval it stops in; a sensor with memory reads it as promised (read_step).
      if (!last) r.world->pass(r.path.path, r.along);
      leave_path(r);
      return true;
    }
    if (block == Block::Wait) {
      r.obstructed += interval;
      if (r.obstructed >= team_.patience_s - 1e-9) {  // gives up its goal: samples here
        // A sensor with memory was promised a reading this interval (read_step): it takes it.
        if (read_step(r) > r.world->steps()) r.world->pass(r.path.path, r.along);
        leave_path(r);
        r.halted = false;
        return true;
      }
      if (sidestep(r, q, last)) return false;
      // A sensor with memory reads where it waits, but not in place of the last part of a
      // path, which reads nothing (read_step).
      if (last)
        r.world->wait(interval);
      else
        r.world->pass(r.path.path, r.along);
      r.halted = true;
      r.out.waited_s += interval;
      return false;
    }
    r.halted = false;
    if (!last) {
      r.world->pass(r.path.path, to);
      r.along = to;
      r.pos = q;
      ++r.tick;
      return false;
    }
    // As SimulatedWorld::travel: whole intervals, then the rest.
    r.world->wait(r.seconds - r.ticks * interval);
    append(r.travelled, r.path.path);
    r.out.distance_m += r.path.length;
    r.pos = r.path.goal;
    return true;
  }

  LocalizationResult result() {
    if (options_.recorder != nullptr) {
      plume_.watch(nullptr);
      for (Robot& r : robots_)
        r.world->watch(nullptr, r.pos);
    }
    LocalizationResult res;
    res.strategy = to_string(team_.strategy);
    res.start = robots_.front().out.start;
    int chosen = declared_by_;
    double best_entropy = std::numeric_limits<double>::infinity(), end_s = 0.0;
    std::vector<double> step_times;
    for (Robot& r : robots_) {
      if (!r.out.steps.empty()) {
        const ste::Posterior& p = posterior(r);
        r.out.estimate = p.expected_source();
        r.out.entropy = p.entropy;
        if (declared_by_ < 0 && p.entropy < best_entropy)
          best_entropy = p.entropy, chosen = r.index;
        end_s = std::max(end_s, r.out.steps.back().time_s);
      } else {
        r.out.estimate = r.out.start;
      }
      res.samples += static_cast<int>(r.out.steps.size());
      res.distance_m += r.out.distance_m;
      res.compute_s += r.compute_s;
      res.decisions_s += r.decisions_s;
      res.plume_s += r.world->busy_s();
      step_times.insert(step_times.end(), r.step_times.begin(), r.step_times.end());
    }
    const Robot& c = robots_.at(static_cast<std::size_t>(chosen));
    res.declared_by = chosen;
    res.stopped_by = declared_by_ >= 0 ? stopped_by_ : "max_samples";
    res.reached = res.stopped_by == "reached";
    res.time_s = declared_by_ >= 0 ? c.out.steps.back().time_s : end_s;
    res.steps = c.out.steps;
    res.posterior = posterior(c);
    res.expected = res.posterior.expected;
    res.estimate = res.posterior.expected_source();
    res.map = res.steps.back().map;
    res.median_step_s = median(step_times);
    for (Robot& r : robots_)
      res.team.push_back(std::move(r.out));
    return res;
  }

  world::SharedPlume& plume_;
  const TeamSetup& setup_;
  const TeamOptions& team_;
  const MethodRunOptions& options_;
  std::vector<Robot> robots_;
  double t_start_ = 0.0;
  bool over_ = false;
  int declared_by_ = -1;
  std::string stopped_by_;
};

}  // namespace

LocalizationResult run_team(world::SharedPlume& plume, const std::vector<Vec2>& starts,
                            const std::vector<methods::LocalizationMethod*>& members,
                            std::uint64_t seed, const TeamSetup& setup, const TeamOptions& team,
                            const MethodRunOptions& options) {
  team.validate();
  TeamRun run(plume, starts, members, seed, setup, team, options);
  return run.run();
}

}  // namespace plumekit::run
