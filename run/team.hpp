#pragma once
// Robot teams (seed 004 ch. 13, Table 13.1): N robots run STE on one map in one world clock, each
// with its own estimator, in the run's one plume.
//
//   individualist: each robot alone; the first declaration ends the mission.
//   cooperative:   every sample is shared, so all robots hold the same data (their posteriors
//                  differ only by MH's draws).
//   collaborative: shared samples plus movement coordination: a robot that picks a goal plans as
//                  if samples had been taken at its teammates' goals (virtual samples, at the
//                  readings its belief predicts there), then swaps goals with a moving teammate
//                  when that lowers the two robots' summed remaining path (task swap).
//
// The world moves every robot at once: one thread steps them in time order, reading by reading
// (each stop's readings, each 0.1 s of travel), so the run is deterministic and every shared
// sample reaches a teammate at the simulated time it was sent. A robot decides when its stop
// ends, after adding the samples its teammates sent before that moment (a tie goes to the lower
// index). Robots keep apart by a separation rule: a robot's goal within `separation` of where a
// teammate stands or is headed moves to the nearest free point that is not (free_goal); a robot
// does not move closer than `separation` to a teammate (may_move). Where a standing teammate
// holds its goal, it samples as close as it gets; where a teammate is in its way, it steps aside
// (45 or 90 degrees, away from the teammate) and replans, or waits when it cannot; after
// `patience_s` obstructed on one way it gives up its goal and samples where it stands.
//
// Metrics as in the thesis: samples (iterations) and distance summed over the robots, mission
// time until the first declaration, the declared estimate's error. A robot whose own sample budget
// runs out (max_samples) stops; the others go on. When none declares, the team's estimate is that
// of the robot whose posterior is most certain (lowest entropy).
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "planner/free_space.hpp"
#include "planner/planner.hpp"
#include "run/method_run.hpp"
#include "run/run_record.hpp"
#include "ste/navigation.hpp"
#include "ste/posterior.hpp"
#include "ste/stop_rule.hpp"
#include "world/shared_plume.hpp"
#include "world/simulated_world.hpp"

namespace plumekit::run {

enum class TeamStrategy { Individualist, Cooperative, Collaborative };
const char* to_string(TeamStrategy strategy);
// "individualist", "cooperative", "collaborative"; OptionError on ste.team.strategy otherwise.
TeamStrategy parse_team_strategy(const std::string& name);

struct TeamOptions {
  int robots = 1;  // 1: a robot alone (the team's code is not used)
  TeamStrategy strategy = TeamStrategy::Individualist;
  // m: no robot moves closer than this to a teammate (the thesis's Khepera IV is 14 cm across:
  // two half bodies and the planner's 0.15 m margin).
  double separation = 0.3;
  // s: a robot obstructed this long on one way (waiting or stepping aside) gives up its goal and
  // samples where it stands (two robots facing each other would otherwise wait for ever): long
  // enough for a teammate in the way to end its 5 s stop and leave.
  double patience_s = 10.0;
  bool shares_samples() const { return strategy != TeamStrategy::Individualist; }
  bool coordinates() const { return strategy == TeamStrategy::Collaborative; }
  // OptionError naming the field (ste.team.robots, ...); ste/options.cpp.
  void validate() const;
};

// The separation rule for a move from `from` to `to` with a teammate at `other`: allowed unless it
// ends closer than `separation` to the teammate and closer than it started (a robot may always
// move away, so robots that start close can part).
bool may_move(Vec2 from, Vec2 to, Vec2 other, double separation);

// The nearest point to `goal` at least `separation` from every point of `taken` (teammates'
// positions and goals): `goal` itself when it is, else the first of 12 points on rings of
// separation / 2, separation, ... (up to 8 rings) about it that `usable` accepts; nullopt when
// none does.
std::optional<Vec2> free_goal(Vec2 goal, const std::vector<Vec2>& taken, double separation,
                              const std::function<bool(Vec2)>& usable);

// The task swap of a collaborative robot at `position` that just chose `goal` (thesis ch. 13 (a)):
// among its moving teammates (their positions and goals), the one whose goal it should take,
// giving it its own, because that lowers the two robots' summed remaining path length (by
// `distance`, the planner's) the most, by more than `min_gain` metres; -1 when no swap does.
struct Heading {
  Vec2 position, goal;
};
int best_swap(const Heading& robot, const std::vector<Heading>& moving,
              const std::function<double(Vec2, Vec2)>& distance, double min_gain = 1e-6);

// Everything a team run shares: its map, world and planner.
struct TeamSetup {
  const Map* map = nullptr;
  Vec2 source;
  const world::WorldOptions* world = nullptr;
  const planner::Planner* planner = nullptr;
  const planner::FreeSpace* space = nullptr;  // where a goal may move (the planner's margin)
};

// One run of a team: robot k starts at starts[k], localizes with members[k] (a method that is a
// Teammate with a posterior: traits.teams; std::logic_error otherwise) and reads with the sensors
// of team_robot_seed(seed, k) in `plume` (built for starts.size() robots from the run's `seed`).
// `options` may end the run when a robot enters its disc (run_method's rule).
LocalizationResult run_team(world::SharedPlume& plume, const std::vector<Vec2>& starts,
                            const std::vector<methods::LocalizationMethod*>& members,
                            std::uint64_t seed, const TeamSetup& setup, const TeamOptions& team,
                            const MethodRunOptions& options);

}  // namespace plumekit::run
