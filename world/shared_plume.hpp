#pragma once
// One filament plume that several robots sample in one world clock. The plume is spun up once;
// after that each robot's world (SimulatedWorld) counts its own steps of the plume's dt as it
// travels and stops, and asks for the plume at its step when it reads a sensor. The plume steps
// on only when every robot still in the world needs a later step, so each robot reads it exactly
// at its own times.
//
// The plume does not depend on the robots (they neither carry nor disturb gas), so a robot reads
// what it would have read alone in a world of the same seed: one plume serves every method of a
// run (`evaluate --method a,b,...`), each at the cost of its own decisions only. Robots that read
// at the same time run on their own threads; a robot alone needs none.
//
// The plume keeps the frames of its latest steps (PlumeFrame: what sensors read then), up to a
// ring's worth, so robots on threads run ahead of one another without waiting at every reading:
// the plume steps when a robot needs a step it has not made, while no robot still needs the frame
// that step overwrites. A robot reads a frame until it asks for a later one.
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <vector>

#include "cfd/wind_field.hpp"
#include "map/map.hpp"
#include "world/filament_model.hpp"

namespace plumekit::world {

// Something that watches a plume step by step (run/replay_recorder.hpp records a replay): told
// the simulation at every `every_steps()`-th step since the spin-up (step 0 included), on the
// thread that steps it. Watching changes nothing of the plume.
class PlumeWatcher {
 public:
  virtual ~PlumeWatcher() = default;
  virtual long long every_steps() const = 0;
  virtual void plume_at(long long step, double time_s, const world::FilamentSimulation& sim) = 0;
};

class SharedPlume {
 public:
  // Builds the plume of `source` (seeded by `seed`) and spins it up
  // (world::spin_up) for `robots` robots, numbered 0 .. robots - 1.
  SharedPlume(const Map& map, const cfd::WindField& wind, Vec2 source,
              const world::FilamentOptions& options, std::uint64_t seed, int robots);
  SharedPlume(const SharedPlume&) = delete;
  SharedPlume& operator=(const SharedPlume&) = delete;

  // The plume's time when the spin-up ended, s since the release.
  double spinup_s() const { return spinup_s_; }
  int robots() const { return static_cast<int>(need_.size()); }

  // The plume `step` steps after the spin-up, for `robot` to read. Blocks while the plume cannot
  // step there yet (another robot still needs the frame that step would overwrite). The frame
  // stays valid until this robot asks for a later step or leaves; a robot's steps never go back
  // (std::logic_error).
  const world::PlumeFrame& at(long long step, int robot);
  // Frames kept: steps a robot may run ahead of the slowest.
  int ring_size() const { return static_cast<int>(ring_.size()); }
  // The robot reads nothing before `step`: the plume need not wait for it until then. A loop that
  // moves several robots on one thread, always the one furthest behind (run/team.hpp), promises
  // each robot's next step after each of its actions, so that at() never waits there.
  void promise(int robot, long long step);
  // The robot reads no more: the plume no longer waits for it.
  void leave(int robot);
  // Lets `watcher` (null: none) watch the steps from now on; it is told the step the plume is at
  // when that is one of its steps.
  void watch(PlumeWatcher* watcher);

 private:
  // Steps the plume to `step`, capturing every frame on the way; called with the lock held,
  // which it releases while it steps (stepping_ keeps other robots from stepping too).
  void advance_to(long long step, std::unique_lock<std::mutex>& g);
  long long earliest_need() const;

  world::FilamentSimulation sim_;
  double spinup_s_ = 0.0;
  long long step_ = 0;                   // the plume's steps since the spin-up: the newest frame's
  std::vector<world::PlumeFrame> ring_;  // frame of step s at s % ring size
  bool stepping_ = false;
  PlumeWatcher* watcher_ = nullptr;
  std::mutex lock_;
  std::condition_variable moved_;
  // Per robot, the earliest step it may still read (its last request); "gone" once it left.
  std::vector<long long> need_;
};

}  // namespace plumekit::world
