// The options table of the simulated world (field names under "ste.world."; the filament plume
// and the gas sensor check their own).
#include "core/option_check.hpp"
#include "world/option_tables.hpp"
#include "world/simulated_world.hpp"

namespace plumekit::world {

namespace {

// How the robot samples on its way and at its stops (issue 47).
std::vector<OptionEntry<WorldOptions>> protocol_entries() {
  using O = WorldOptions;
  return {{"ste.world.read_while_moving",
           "--read-while-moving",
           &O::read_while_moving,
           {},
           "The gas sensor reads at its rate along every path too, and the method gets those "
           "readings with each stop's (issue 47; STE averages them over --passing-window; "
           "localize and evaluate: --protocol, true unless thesis)"},
          {"ste.world.adaptive_stop",
           "--adaptive-stops",
           &O::adaptive_stop,
           {},
           "A stop lasts from --stop-min-s to --stop-s: until its mean is known to within "
           "--stop-tolerance (issue 47; world/simulated_world.hpp; localize and evaluate: "
           "--protocol, true unless thesis)"},
          {"ste.world.stop_min_s", "--stop-min-s", &O::stop_min_s, positive(3600.0, "s"),
           "Adaptive stops: the shortest stop, s"},
          {"ste.world.stop_tolerance", "--stop-tolerance", &O::stop_tolerance,
           non_negative(1e9, "concentration units"),
           "Adaptive stops: a stop ends once the standard error of its mean (from its half-second "
           "means) is at most this, concentration units"}};
}

// The world's noises and errors, and the robot's pace.
std::vector<OptionEntry<WorldOptions>> sensing_entries() {
  using O = WorldOptions;
  std::vector<OptionEntry<O>> entries{
      {"ste.world.noise", "--noise", &O::noise, non_negative(1e9, "concentration units"),
       "Sensor noise std per reading (simulated)", "0 means a noise-free sensor"},
      {"ste.world.speed", "--speed", &O::speed, positive(100.0, "m/s"), "Robot speed, m/s"},
      {"ste.world.sample_s", "--stop-s", &O::sample_s, positive(3600.0, "s"),
       "Length of each stop's sampling, s (seed 004 and the thesis: 5; seed 000: 20)",
       "the thesis uses 5 s"},
      {"ste.world.sample_rate", "--stop-rate", &O::sample_rate, positive(1000.0, "Hz"),
       "Readings per second during a stop, Hz (seed 004 and the thesis: 10; seed 000: 1)",
       "the thesis uses 10 Hz"},
      {"ste.world.wind_direction_noise", "", &O::wind_direction_noise_deg,
       non_negative(360.0, "degrees"),
       "Anemometer direction error per stop: std, degrees (localize's --wind-noise, which also "
       "takes table35)",
       "0 is an exact anemometer; seed 000 measured 14-29 degrees"},
      {"ste.world.wind_noise_from_table35",
       "",
       &O::wind_noise_from_table35,
       {},
       "Take the direction error from seed 000's Table 3.5 at the stop's length"},
      {"ste.world.wind_variance_noise", "--wind-variance-noise", &O::wind_variance_noise_deg,
       non_negative(360.0, "degrees"),
       "Direction noise on each single wind reading of a stop, degrees, from which the stop's "
       "circular variance (the particle filter's) is computed (seed 002: 23.08; 0: the "
       "world's own wind)",
       "0 takes the circular variance from the world's own wind; seed 002 used 23.08"},
      {"ste.world.position_noise", "", &O::position_noise, non_negative(100.0, "m"),
       "Std per axis of the position recorded with each stop, m (localize's --position-noise, "
       "which also takes gps)",
       "0 is an exact position; seed 000's GPS (Eq. 4.3) is 1.08 m"},
      {"ste.world.position_noise_per_fix",
       "",
       &O::position_noise_per_fix,
       {},
       "position_noise is each reading's fix's error, and a stop records their mean"},
      {"ste.world.odometry_drift", "--odometry-drift", &O::odometry_drift,
       non_negative(1.0, "m per sqrt(m)"),
       "The position a stop records drifts from the true one by a random walk of this std per "
       "axis per square root of metre travelled, m (odometry without a positioning system, "
       "for ste-local; 0: the true position)",
       "0 records the true position"},
      {"ste.world.rotor_disc", "--rotor-disc", &O::rotor_disc, non_negative(10.0, "m"),
       "Each gas reading averages the concentration over a disc of this radius, m (seed 000's "
       "rotor disturbance: 0.5; 0: at the sensor's point)",
       "0 reads at a point; seed 000's rotor disturbance is 0.5 m"}};
  return entries;
}

}  // namespace

const OptionTable<WorldOptions>& world_option_table() {
  static const OptionTable<WorldOptions> table = [] {
    OptionTable<WorldOptions> t{"Simulated world (world::WorldOptions)", sensing_entries()};
    for (OptionEntry<WorldOptions>& e : protocol_entries())
      t.entries.push_back(std::move(e));
    return t;
  }();
  return table;
}

void WorldOptions::validate() const {
  filament.validate();
  sensor.validate();
  plumekit::validate(world_option_table(), *this);
}

}  // namespace plumekit::world
