#pragma once
// The random streams of a localization run, in one place. Every run has one
// seed (run_seed); each consumer draws from its own stream of it, so that, for
// example, sensor noise never shifts the plume. The stream values are those
// the committed evaluation results were made with (results/): changing one
// changes every run.
#include <cstdint>

#include "core/seed.hpp"

namespace plumekit::world {

// Counter-based seeds: one per (seed, map, source, run), whatever thread runs it.
inline std::uint64_t run_seed(std::uint64_t seed, std::uint64_t map, std::uint64_t source,
                              std::uint64_t run) {
  return splitmix64(splitmix64(splitmix64(splitmix64(seed) ^ map) ^ source) ^ (run + 0x57E));
}

// What a run's seed is XORed with for each consumer. The filament plume takes the run's seed
// itself.
enum class SteStream : std::uint64_t {
  Start = 0xA5A5,                // the random start (Scenario::random_start)
  SensorNoise = 0x5DEECE66DULL,  // the simulated sensor's noise (SimulatedWorld)
  Mh = 0x3C,                     // the Metropolis-Hastings chain, through splitmix64 (MhEstimator)
  WindNoise = 0xA7E3,            // the anemometer's direction error (SimulatedWorld)
  PositionNoise = 0x905E,        // the recorded position's error (SimulatedWorld)
  Method = 0x9F17,               // a localization method's own draws (the particle filter)
  WindSpread = 0x5A0D,           // the single wind readings' direction noise (SimulatedWorld)
  TeamRobot = 0x7EA3,            // a team's robots after the first (team_robot_seed)
  Odometry = 0x0D0E,             // the odometry's drift (SimulatedWorld)
  TransitNoise = 0x7A5E,         // the sensor noise of readings while moving (SimulatedWorld)
  TransitPosition = 0x7A90,      // the recorded position's error of readings while moving
};

inline std::uint64_t stream_seed(std::uint64_t run_seed, SteStream stream) {
  return run_seed ^ static_cast<std::uint64_t>(stream);
}

// The seed of robot k of a team in run `run_seed`: its sensors' streams and its MH chain draw from
// it (the plume is the run's). Robot 0's is the run's own, so a team of one is the lone robot.
inline std::uint64_t team_robot_seed(std::uint64_t run_seed, int robot) {
  if (robot == 0) return run_seed;
  return splitmix64(stream_seed(run_seed, SteStream::TeamRobot) +
                    static_cast<std::uint64_t>(robot));
}

}  // namespace plumekit::world
