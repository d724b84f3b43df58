#pragma once
// The 3-D world of seed 004's chs. 11 and 17: a robot flying in a wind tunnel with a uniform wind
// (the thesis's Khepera with gravity off, or on the tunnel's traversing system), sampling the 3-D
// filament plume of world/tunnel_plume.hpp. It extends the 2-D world (world.hpp) by a third
// axis and keeps its rules and options (WorldOptions): the plume is spun up and then runs on in
// time while the robot travels at `speed`; a stop is the mean of `sample_s` of readings at
// `sample_rate` Hz through the gas sensor's response, with Gaussian noise clipped at 0; the
// recorded position takes `position_noise` per axis. New here: the robot also reads while it
// moves (a move's mean reading), as the bio-inspired trackers of ch. 17 do at constant speed.
// The options that need a map (the rotor disc, odometry, the anemometer's direction noise and
// circular variance) are not offered: the tunnel's wind is the uniform one plus the meander.
#include <cstdint>
#include <random>

#include "core/geometry.hpp"
#include "world/gas_sensor.hpp"
#include "world/simulated_world.hpp"
#include "world/tunnel_plume.hpp"

namespace plumekit::world {

// What the robot's sensors report for a stop or a move: Reading with a third axis.
struct Reading3 {
  double gas = 0.0;  // the mean gas reading
  Vec3 wind;         // the anemometer's mean wind
  Vec3 position;     // where the robot records it (with position noise)
};

// OptionError naming "tunnel.world.<field>" for a WorldOptions field the tunnel does not offer
// (not at its default), else WorldOptions::validate().
void validate_tunnel_world(const WorldOptions& options);

// Watches a tunnel run (a replay's recorder, run/tunnel_replay.hpp): every every_steps() plume
// steps from the robot's start (step 0), the plume and where the robot is then.
class TunnelWatcher {
 public:
  virtual ~TunnelWatcher() = default;
  virtual long long every_steps() const = 0;
  virtual void frame(long long step, double time_s, const TunnelPlume& plume, Vec3 robot) = 0;
};

class TunnelWorld {
 public:
  // The plume of `source` (seeded by `seed`) with options.filament, spun up; the sensors draw
  // from streams of `seed` (world/random_streams.hpp).
  TunnelWorld(const world::Tunnel& tunnel, Vec3 source, const WorldOptions& options,
              std::uint64_t seed);
  // Flies straight from `from` to `to` at options.speed while the plume runs on; a sensor with
  // memory reads on the way (the ideal one reads nothing).
  void travel(Vec3 from, Vec3 to);
  // Stays at p for sample_s and returns what the sensors report.
  Reading3 stop(Vec3 p);
  // Flies straight from `from` to `to` at `speed` m/s reading at sample_rate, and returns the
  // mean of the readings (at least one, at `to`) and the mean wind: a tracker's reading on the
  // move.
  Reading3 move(Vec3 from, Vec3 to, double speed);
  double time() const { return time_; }  // simulated seconds since the robot started
  Vec3 source() const { return source_; }
  const world::Tunnel& tunnel() const { return plume_.tunnel(); }
  const WorldOptions& options() const { return options_; }
  double spinup_s() const { return spinup_s_; }
  // Shows the run to `watcher` (null: nobody) from the robot's start on; the run is the same.
  void watch(TunnelWatcher* watcher) { watcher_ = watcher; }

 private:
  // The plume runs on `seconds` while the robot goes straight from `from` to `to`.
  void advance(double seconds, Vec3 from, Vec3 to);
  // One reading at p, then one reading interval passes.
  double read(Vec3 p);
  // n readings at the points k / n of the way from `from` to `to` (k = 1 .. n; all at `to` for a
  // stop) and their means, recorded at `to`.
  Reading3 readings(Vec3 from, Vec3 to, int n);
  Vec3 recorded(Vec3 p, double sd);

  world::TunnelPlume plume_;
  Vec3 source_;
  WorldOptions options_;
  world::GasSensor gas_;
  std::mt19937_64 noise_rng_, position_rng_;
  NormalSampler noise_, position_;
  double time_ = 0.0, debt_ = 0.0, spinup_s_ = 0.0;
  TunnelWatcher* watcher_ = nullptr;
  long long steps_ = 0;  // plume steps since the robot started
  bool started_ = false;
};

}  // namespace plumekit::world
