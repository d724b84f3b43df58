#pragma once
// The run loop: sense, decide, move. Every run in plumekit goes through act() below: one robot
// with any floor method (run_method: stop and read the sensors, let the method observe and
// decide, drive to its goal along a planner path around the obstacles, record every stop), each
// robot of a team (team.hpp: the same phases, interleaved in the world's time), and the tunnel's
// 3-D methods (tunnel_run.hpp). What differs between them is what a phase does, not their order.
#include <optional>

#include "core/interrupt.hpp"
#include "methods/method.hpp"
#include "planner/free_space.hpp"
#include "planner/planner.hpp"
#include "run/run_record.hpp"
#include "world/simulated_world.hpp"

namespace plumekit::run {

// Where a robot is in its loop.
enum class Phase { Sense, Decide, Move, Done };

// One action of `robot` in `phase`, and the phase it is in after it. A Robot has
//   bool sense():  reads (part of) a stop; true once the stop's reading is complete;
//   bool decide(): the method observes the reading, the stop rules apply, a move is chosen;
//                  true when the robot's run ends there;
//   bool move():   moves (part of) the way; true once the move is over.
// A robot alone may do a whole phase per call; a team's robots do a reading interval each, so
// that the one thread that steps them keeps them in time order (team.cpp).
template <class Robot>
Phase act(Robot& robot, Phase phase) {
  switch (phase) {
    case Phase::Sense:
      check_interrupt();  // a caller's Ctrl-C (core/interrupt.hpp)
      return robot.sense() ? Phase::Decide : Phase::Sense;
    case Phase::Decide:
      return robot.decide() ? Phase::Done : Phase::Move;
    case Phase::Move:
      return robot.move() ? Phase::Sense : Phase::Move;
    case Phase::Done:
      break;
  }
  return Phase::Done;
}

// A robot alone: its phases in turn until its run ends.
template <class Robot>
void run_loop(Robot& robot) {
  for (Phase phase = Phase::Sense; phase != Phase::Done;)
    phase = act(robot, phase);
}

// The plume trackers' success area (seed 002 §5.1): 1.5 m along the wind by 2 m across it,
// right downwind of the source. A tracker cannot know the source; the runner ends its run when a
// stop lies in this box ("reached").
struct SourceBox {
  Vec2 source;
  Vec2 downwind{1.0, 0.0};  // unit vector: the mean wind's direction at the source
  double along = 1.5, across = 2.0;
  bool contains(Vec2 p) const;
};

// Seed 004 ch. 15's success area: a disc about the source (0.5 m in ch. 16). The runner ends a run
// as soon as the robot enters it, on its way too: a move that passes through it stops there.
struct SourceDisc {
  Vec2 source;
  double radius = 0.5;
  bool contains(Vec2 p) const { return norm(p - source) <= radius; }
  // Where `path` first enters the disc: on its leg from point `leg` - 1 to point `leg`, at the
  // fraction `t` of it, `along` metres from the path's start (0 when it starts inside); nullopt
  // when it never enters it.
  struct Entry {
    std::size_t leg = 0;
    double t = 0.0, along = 0.0;
  };
  std::optional<Entry> entry(const std::vector<Vec2>& path) const;
};

// CPU time of the calling thread, s: a decision step runs on one thread, and this reads the same
// on a loaded machine as on a quiet one.
double thread_cpu_s();
// Wall-clock seconds (a steady clock): the times a run's report adds up (LocalizationResult).
double wall_clock_s();

// The world's readings on the way as a run records them (times since `t_start`, the robot's
// start), and as a method observes them (at their recorded points).
std::vector<PassingRecord> passing_records(const std::vector<world::TransitReading>& readings,
                                           double t_start);
std::vector<methods::BasicPassing<Vec2>> passing_observations(
    const std::vector<PassingRecord>& records);

// `path` cut at its first point in `disc` (unchanged when it never enters it): a run ends where
// its robot enters the disc.
void cut_at_entry(const SourceDisc& disc, planner::PlanResult& path);

class ReplayRecorder;  // run/replay_recorder.hpp

struct MethodRunOptions {
  std::optional<SourceBox> box;    // stop a run whose stop lies in it
  std::optional<SourceDisc> disc;  // stop a run where it enters it
  // Moves goals off obstacles and walls (the planner's margin); needed by every method that does
  // not plan its own paths (all but STE).
  const planner::FreeSpace* space = nullptr;
  // A guard on every method (each has its own budget below this): no run is longer.
  int max_stops = 2000;
  // After the method stops (other than by reaching the source), the robot drives to its estimate,
  // when it has one, and the mission ends there: a robot that has found a leak goes to it, and
  // GSL-Bench scores where the robot is (issue 47; SteOptions::approach).
  bool approach = false;
  // Records the run's replay (the world's frames and each decision's belief); null: none.
  ReplayRecorder* recorder = nullptr;
};

// Why a run ends at its `stops`-th stop, made at `pos`: the method's own reason, or the runner's
// ("reached": the stop lies in the options' source box or disc; "max_samples": the stop budget);
// "" while it goes on. A robot alone and each robot of a team end by this rule.
std::string stop_reason(const methods::LocalizationMethod& method, Vec2 pos, int stops,
                        const MethodRunOptions& options);

// One run of `method` from `start`. A goal the robot cannot reach leaves it where it is (the
// method sees that in its next observation). The result's estimate is the method's, or where the
// robot ended for a method without one (a plume tracker).
LocalizationResult run_method(Vec2 start, methods::LocalizationMethod& method,
                              world::SimulatedWorld& world, const planner::Planner& planner,
                              const MethodRunOptions& options);

}  // namespace plumekit::run
