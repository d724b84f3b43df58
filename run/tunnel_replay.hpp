#pragma once
// A tunnel run's replay (run/replay.hpp with its view from the side, docs/replay.md, "The
// tunnel"), recorded while the run goes: the world shows the recorder the plume and the robot
// every frame (world::TunnelWatcher), the run hands it STE's posterior after each decision, and
// the run's record gives the readings and the end. The run is the same with or without it.
#include <optional>
#include <string>
#include <vector>

#include "run/replay.hpp"
#include "run/tunnel_run.hpp"
#include "world/tunnel_world.hpp"

namespace plumekit::run {

// The tunnel from above as a map: its length along x, its width along y, the inlet on the left
// wall at the tunnel's wind and the outlet on the right.
Map tunnel_map(const world::Tunnel& tunnel);

class TunnelReplayRecorder : public world::TunnelWatcher {
 public:
  // Frames every `every_s` simulated seconds (whole plume steps of the tunnel's dt) of the plane
  // through `source` seen from above (z = source.z) and from the side (y = source.y), on cells of
  // about 0.1 m; STE's stops last `sample_s`.
  TunnelReplayRecorder(const world::Tunnel& tunnel, Vec3 source, double every_s, double dt,
                       double sample_s);

  long long every_steps() const override { return every_steps_; }
  void frame(long long step, double time_s, const world::TunnelPlume& plume, Vec3 robot) override;
  // STE's posterior after its decision at `time_s` (a tracker holds none: null).
  void belief(double time_s, const ste::Posterior3* posterior);

  // The replay of the finished `run`; `title` says which run.
  Replay finish(const TunnelRun& run, const std::string& title) const;

 private:
  world::Tunnel tunnel_;
  Vec3 source_;
  long long every_steps_;
  double every_s_, sample_s_;
  GridShape top_grid_, side_grid_;
  std::vector<std::vector<float>> top_, side_;  // per frame
  std::vector<std::optional<Vec3>> where_;      // per frame
  GridShape belief_top_grid_, belief_side_grid_;
  std::vector<ReplayBelief> beliefs_;
  std::vector<double> side_peaks_;
  std::vector<std::uint8_t> belief_top_, belief_side_;
};

// The recorder of a run of `options` to find `source`: a frame a second.
TunnelReplayRecorder tunnel_replay_recorder(const TunnelOptions& options, Vec3 source);

// The replay's title: the tunnel, the method, the source and the seed.
std::string tunnel_replay_title(const TunnelOptions& options, Vec3 source, std::uint64_t seed);

}  // namespace plumekit::run
