#pragma once
// Records a run's replay (run/replay.hpp) while the run goes: the world tells it where each robot
// is and what the plume is at every frame (world::WorldWatcher), the run loop hands it the
// method's belief after each decision, and the run's result gives the stops, the readings and the
// end. Recording reads what the run computes anyway plus one concentration grid per frame; the
// run itself is the same with or without it.
#include <memory>
#include <mutex>
#include <vector>

#include "methods/method.hpp"
#include "run/replay.hpp"
#include "run/run_record.hpp"
#include "world/simulated_world.hpp"

namespace plumekit::run {

class Scenario;  // run/scenario.hpp

// The top of the replay's log scale for these concentration frames (and those of a second view,
// `more`, on the same scale): the 99.9th percentile of the concentrations above
// kReplayPlumeFloor (one hot cell at the source would otherwise squeeze the whole plume into a
// few levels), at least 10 floors.
double replay_plume_top(const std::vector<std::vector<float>>& frames,
                        const std::vector<std::vector<float>>& more = {});
// Makes `frames` `count` long: a frame the world did not show (nobody had stepped the plume to
// it) shows the one before it, no gas before the first.
void fill_unseen_frames(std::vector<std::vector<float>>& frames, std::size_t count,
                        std::size_t cells);
// Appends each frame's cells on `scale`'s log levels (Replay::plume_level) to `levels`.
void append_plume_levels(const Replay& scale, const std::vector<std::vector<float>>& frames,
                         std::vector<std::uint8_t>& levels);

class ReplayRecorder : public world::WorldWatcher {
 public:
  // Frames every `every_s` simulated seconds (rounded to whole plume steps of `dt`), from the
  // world's step 0, where the robots start. The world numbers the robots from `first_robot` (a
  // method's robot in a plume several methods share is its method's slot there).
  ReplayRecorder(const Map& map, int robots, double every_s, double dt, int first_robot = 0);

  long long every_steps() const override { return every_steps_; }
  void plume_at(long long step, double time_s, const world::FilamentSimulation& sim) override;
  void robot_at(int robot, long long step, double time_s, Vec2 where) override;
  // The plume's frames `other` recorded, as this one's (the robots of several methods in one
  // shared plume, which only one recorder watches: evaluate --method a,b --replays).
  void copy_plume_frames(const ReplayRecorder& other);
  // Robot `robot`'s method after its decision at `time_s` (since the robots started).
  void belief(int robot, double time_s, const methods::LocalizationMethod& method);

  // The replay of the finished run `result` with its true `source`; `title` says which run.
  Replay finish(const LocalizationResult& result, Vec2 source, const std::string& title);

 private:
  const Map& map_;
  int robots_, first_robot_;
  long long every_steps_;
  double every_s_;
  GridShape plume_grid_;
  mutable std::mutex lock_;  // a plume shared with other robots may step on another thread
  std::vector<std::vector<float>> plume_;                // per frame; empty: not seen
  std::vector<std::vector<std::optional<Vec2>>> where_;  // per frame, per robot
  std::vector<double> scratch_;
  GridShape belief_grid_;
  std::vector<ReplayBelief> beliefs_;
  std::vector<std::uint8_t> belief_cells_;
  bool has_estimate_ = false;
};

// The recorder of a run of `scenario`: its robots, a frame a second on its plume's steps; the
// world numbers its robots from `first_robot` (see the constructor).
std::unique_ptr<ReplayRecorder> replay_recorder_for(const Scenario& scenario, int first_robot = 0);

}  // namespace plumekit::run
