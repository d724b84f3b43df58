#pragma once
// The simulated world a robot samples: the filament plume of the true source
// in the map's wind (world/filament_model.hpp), spun up until statistically
// steady and then kept running in time while the robot travels and samples.
// A sample is the mean of `sample_s` of readings at `sample_rate` Hz at
// the robot's position, each reading through the gas sensor's response
// (world/gas_sensor.hpp; ideal by default) and optionally with Gaussian
// sensor noise (clipped at 0: a sensor reads no negative concentration).
// A sensor with memory also reads on the way between stops, so it arrives
// with what the path left in it; the ideal one only reads at stops.
//
// Readings while moving (issue 47; WorldOptions::read_while_moving): every
// sensor, the ideal one included, then reads at its own rate along every path,
// and the world records each reading (TransitReading, take_transit_readings).
// Where: the point the robot has reached at the end of each reading interval
// of travel (pass(); travel() is pass() for each whole interval of the path,
// then a wait for the rest). When: the world's time() then, the plume step the
// reading is of. What: the sensor's response to the exposure there (so the
// sensor's lag is part of the record) plus Gaussian noise of `noise` clipped at
// 0, as a stop's single readings, but drawn from a stream of its own
// (SteStream::TransitNoise), so the stops draw exactly what they drew without.
#include <cstdint>
#include <memory>
#include <random>
#include <vector>

#include "cfd/wind_field.hpp"
#include "core/random.hpp"
#include "map/map.hpp"
#include "world/filament_model.hpp"
#include "world/gas_sensor.hpp"
#include "world/shared_plume.hpp"

namespace plumekit::world {

struct WorldOptions {
  world::FilamentOptions filament;  // the dataset's plume (release rate 1000)
  double speed = 0.5;               // m/s, the robot's travel speed
  double sample_s = 5.0;            // thesis: 5 s ...
  double sample_rate = 10.0;        // ... at 10 Hz
  double noise = 0.0;               // std of each reading's sensor noise, dataset units
  world::GasSensorModel sensor;     // the gas sensor's response (--gas-sensor); ideal
  // Std of the anemometer's direction error per stop, degrees (the speed is
  // exact, as in seed 000 Eq. 4.11); table35_direction_noise gives the seed's
  // measured values by averaging time.
  double wind_direction_noise_deg = 0.0;
  bool wind_noise_from_table35 = false;  // use table35_direction_noise(sample_s) instead
  double direction_noise_deg() const;
  // Std of a direction noise on each of a stop's single wind readings, degrees: the stop's
  // circular variance S0 (Reading::wind_variance) is then that of the noisy directions, as seed
  // 002 synthesised it (σ_S0 = 23.08, read as a standard deviation; docs/methods.md). 0: S0 of
  // the world's own wind.
  double wind_variance_noise_deg = 0.0;
  // Std per axis of the position the robot records for a stop, m
  // (kGpsPositionNoise is seed 000's GPS); the robot still drives from where it is.
  double position_noise = 0.0;
  // position_noise is the error of each reading's fix, independent from reading to reading,
  // and the stop records the mean of its fixes (std position_noise / sqrt(readings)): seed 000
  // perturbed every 1 Hz sample's position (--position-noise gps). false: one error per stop.
  bool position_noise_per_fix = false;
  // Odometry (seed 004 ch. 12's local framework): the position a stop records drifts from the
  // true one by a random walk of this std per axis per square root of metre travelled, m/sqrt(m)
  // (the robot's own estimate from its start, without a positioning system). 0: none.
  double odometry_drift = 0.0;
  // Radius of the disc over which each gas reading averages the concentration, m: seed 000
  // §4.4's rotor disturbance (0.5 m, the drone's downwash mixing the air under it before the
  // sensor model). 0: the concentration at the sensor's point.
  double rotor_disc = 0.0;
  // Record a reading at every reading interval of travel, whatever the sensor (see above). Off
  // here, every draw, plume step and reading is as it was before issue 47 (a sensor with memory
  // still reads on the way, unrecorded); localize and evaluate turn it on (run::SteOptions'
  // protocol, moving by default).
  bool read_while_moving = false;
  // Adaptive stops (issue 47): a stop lasts from stop_min_s to sample_s, and ends at the first
  // whole second from stop_min_s on when its mean is known to within stop_tolerance: the standard
  // error of its mean, from the spread of its half-second means, is at most that (more readings
  // would not move the mean by more). In clean air that is stop_min_s; where the plume comes and
  // goes, up to sample_s. A stop lasts whole seconds, at least one (two half-second means), so a
  // pass-through is not offered: a decision needs its stop's reading. Off: every stop lasts
  // sample_s. Off here; on in localize and evaluate (their moving protocol).
  bool adaptive_stop = false;
  double stop_min_s = 1.0;       // s
  double stop_tolerance = 20.0;  // concentration units
  // OptionError naming the field (docs/methods.md, "Options"); ste/options.cpp.
  void validate() const;
};

// Seed 000 Eq. 4.3, its GPS: each recorded coordinate is drawn from N(x, σ²)
// with "σ² set to 1.17", so the std per axis is sqrt(1.17) m, on every sample's fix
// (--position-noise gps: with position_noise_per_fix).
constexpr double kGpsPositionNoise = 1.0816653826391969;

// The 19 points whose equal-weight mean is plumekit's mean over a disc of `radius` about
// `centre` (rotor_disc): the centre, 6 and 12 points on the rings that halve the area each
// stands for, so every point stands for 1/19 of the disc. Exact for linear fields; off by 0.3 %
// for the disc's mean square radius.
std::vector<Vec2> disc_points(Vec2 centre, double radius);

// Seed 000, Table 3.5 (hovering): the wind direction's RMSE after averaging
// over 0, 5, 10 and 20 s is 29.12, 22.26, 17.76 and 14.02 degrees; linear in
// between, 14.02 beyond 20 s.
double table35_direction_noise(double averaging_s);

// What the robot's sensors report for one stop: the interface the
// localization methods read the world through.
struct Reading {
  double gas = 0.0;  // the mean gas reading over the stop
  Vec2 wind;         // the anemometer's mean wind over the stop, with its direction error
  // The circular variance S0 = 1 - R of the wind's direction over the stop's readings (seed 000
  // App. A): 0 in a steady wind, larger where it meanders.
  double wind_variance = 0.0;
  Vec2 position;  // where the robot records the stop: its position plus position noise
};

// One reading taken on the way between stops (read_while_moving), at the end of a reading
// interval of travel.
struct TransitReading {
  Vec2 position;  // the true point the robot had reached
  // Where the robot records it: the true point plus, with position_noise, one fix's error (std
  // position_noise per axis, independent from reading to reading, redrawn until free, from
  // SteStream::TransitPosition), plus with odometry_drift the drift so far: the drift before the
  // leg and the share of the leg's drift (travel() draws it whole) that the metres covered stand
  // for, the random walk's mean given both ends.
  Vec2 recorded;
  double time_s = 0.0;  // SimulatedWorld::time() at the reading
  double value = 0.0;   // the gas sensor's reading, with its noise (>= 0)
};

// Something that watches a robot as its world's time passes, for a replay of the run
// (run/replay_recorder.hpp): told where the robot truly is at every `every_steps()`-th plume step
// since the spin-up that its time reaches (step 0 included), and, as a PlumeWatcher, the plume at
// those steps. Watching changes nothing of the run.
class WorldWatcher : public PlumeWatcher {
 public:
  virtual void robot_at(int robot, long long step, double time_s, Vec2 where) = 0;
};

class SimulatedWorld {
 public:
  // A world of its own: the plume of `source` seeded by `seed`, spun up.
  SimulatedWorld(const Map& map, const cfd::WindField& wind, Vec2 source,
                 const WorldOptions& options, std::uint64_t seed);
  // Robot `robot` in a plume it shares (world/shared_plume.hpp), which must have been built with
  // options.filament and `seed` on this map: the robot then reads exactly what it would read in
  // the world of its own above. Its sensors draw from the streams of `seed`.
  SimulatedWorld(SharedPlume& plume, int robot, const Map& map, Vec2 source,
                 const WorldOptions& options, std::uint64_t seed);
  ~SimulatedWorld();
  SimulatedWorld(const SimulatedWorld&) = delete;
  SimulatedWorld& operator=(const SimulatedWorld&) = delete;

  // The plume runs on while the robot covers `path` (`metres` long) at
  // options.speed; a sensor with memory reads along it.
  void travel(const std::vector<Vec2>& path, double metres);
  // Stays at p for sample_s and returns what the sensors report.
  Reading stop(Vec2 p);

  // The same in steps, for a loop that interleaves several robots in one plume reading by reading
  // (run/team.hpp). stop(p) is begin_stop(p), stop_reading() until it returns true, end_stop();
  // travel() is pass() for each reading interval of the path, then wait() for the rest.
  void begin_stop(Vec2 p);
  // Takes the stop's next reading now, then lets one reading interval pass; true once the stop's
  // readings are all taken (with adaptive_stop, once its mean is settled).
  bool stop_reading();
  // What the stop's readings report (the direction and position errors drawn now).
  Reading end_stop();
  // One reading interval of travel: a sensor with memory (any sensor, with read_while_moving)
  // reads at the point `along` metres along `path` at its end; with read_while_moving the
  // reading is recorded.
  void pass(const std::vector<Vec2>& path, double along);
  // The readings recorded on the way since the last call, oldest first; forgets them.
  std::vector<TransitReading> take_transit_readings();
  // Time passes; the robot reads nothing.
  void wait(double seconds) { advance(seconds); }
  double reading_interval() const { return 1.0 / options_.sample_rate; }
  // The plume step the robot's next reading is at (steps of the plume's dt since the spin-up).
  long long steps() const { return steps_; }
  // The plume step the robot will be at after `seconds` more (what wait(seconds) leads to).
  long long steps_after(double seconds) const;
  // Whether the gas sensor reads on the way (one with memory, or any with read_while_moving):
  // pass() then reads the plume.
  bool reads_while_travelling() const { return gas_.has_memory() || options_.read_while_moving; }
  const WorldOptions& options() const { return options_; }
  double time() const { return time_; }                  // simulated seconds since release
  double spinup_s() const { return plume_.spinup_s(); }  // before the robot started
  Vec2 source() const { return source_; }
  const Map& map() const { return map_; }
  // Wall-clock seconds spent in travel(), pass(), stop() and stop_reading(): the plume's steps
  // and the sensors' readings (with a shared plume, waits for the other robots too).
  double busy_s() const { return busy_s_; }
  // Lets `watcher` (null: none) watch the robot, which is at `where` now (and the plume, in a
  // world of its own; a shared plume is watched through SharedPlume::watch). It is told the
  // step the world is at first, when that is one of its steps.
  void watch(WorldWatcher* watcher, Vec2 where);

 private:
  // One of `own` (a world of its own) and `shared`.
  SimulatedWorld(std::unique_ptr<SharedPlume> own, SharedPlume* shared, int robot, const Map& map,
                 Vec2 source, const WorldOptions& options, std::uint64_t seed);
  void advance(double seconds);
  // The plume at this robot's time.
  const world::PlumeFrame& plume() { return plume_.at(steps_, robot_); }
  // The concentration the gas sensor is exposed to at p: at the point, or the rotor disc's mean
  // over its free points.
  double exposure(const world::PlumeFrame& plume, Vec2 p) const;
  // p plus a fix's error of std `sd` per axis from `rng`, redrawn until free: a robot does not
  // believe itself inside a wall it can see (p if 1000 draws are not).
  Vec2 fix(Vec2 p, double sd, std::mt19937_64& rng) const;
  // Whether the stop under way may end now (adaptive_stop): see WorldOptions.
  bool stop_settled() const;
  // Records the reading `value` the sensor gave at p, `along` metres into the path.
  void record_transit(Vec2 p, double along, double value);
  // Tells the watcher where the robot is at step steps_ (time_).
  void notify_watcher();
  // Adds the wall time of the outermost timed call to busy_s_ (stop() calls stop_reading()).
  class Busy;
  double busy_s_ = 0.0;
  int busy_depth_ = 0;
  std::unique_ptr<SharedPlume> own_;  // a world of its own
  SharedPlume& plume_;
  int robot_ = 0;
  Vec2 source_;
  WorldOptions options_;
  const Map& map_;
  std::mt19937_64 noise_rng_, wind_rng_, position_rng_, spread_rng_, odometry_rng_;
  // The readings on the way draw from streams of their own, so the stops' draws are the same
  // with read_while_moving on and off.
  std::mt19937_64 transit_noise_rng_, transit_position_rng_;
  NormalSampler transit_noise_;
  std::vector<TransitReading> transit_;  // since take_transit_readings()
  world::GasSensor gas_;
  long long steps_ = 0;  // of the plume's dt since the spin-up
  double time_ = 0.0;    // summed step by step, as the plume sums its own
  double debt_ = 0.0;    // seconds not yet stepped (travel times are not multiples of dt)
  Vec2 odometry_error_;  // the recorded position's drift so far (odometry_drift)
  // For a watcher: where the robot is, or the path travel() is covering and when it set off.
  WorldWatcher* watcher_ = nullptr;
  Vec2 where_;
  struct Way {
    const std::vector<Vec2>* path = nullptr;
    double metres = 0.0, set_off = 0.0;
  } way_;
  // The leg travel() is on, for the drift a reading on the way records: the drift before it and
  // after it, and its metres.
  struct Leg {
    Vec2 from, to;
    double metres = 0.0;
    bool active = false;
  } leg_;
  // The stop under way (begin_stop .. end_stop).
  struct StopState {
    Vec2 p;
    int readings = 0, taken = 0;
    double sum = 0.0;
    std::vector<double> values;   // each reading's, with adaptive_stop
    Vec2 wind_sum;                // the wind that carries the gas at p, at each reading
    Vec2 direction_sum;           // their unit vectors: the circular variance
    NormalSampler noise, spread;  // a fresh pair per sample, as the committed results were drawn
  } stop_;
};

}  // namespace plumekit::world
