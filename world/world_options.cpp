// The range checks of the simulated world's options (field names under "ste.world."; the
// filament plume and the gas sensor check their own).
#include "core/option_check.hpp"
#include "world/simulated_world.hpp"

namespace plumekit::world {
void WorldOptions::validate() const {
  filament.validate();
  check_positive("ste.world.speed", speed, 100.0, "m/s", "the default is 0.5 m/s");
  check_positive("ste.world.sample_s", sample_s, 3600.0, "s", "the thesis uses 5 s");
  check_positive("ste.world.sample_rate", sample_rate, 1000.0, "Hz", "the thesis uses 10 Hz");
  check_non_negative("ste.world.noise", noise, 1e9, "concentration units",
                     "0 means a noise-free sensor");
  sensor.validate();
  check_non_negative("ste.world.wind_direction_noise", wind_direction_noise_deg, 360.0, "degrees",
                     "0 is an exact anemometer; seed 000 measured 14-29 degrees");
  check_non_negative("ste.world.wind_variance_noise", wind_variance_noise_deg, 360.0, "degrees",
                     "0 takes the circular variance from the world's own wind; seed 002 used "
                     "23.08");
  check_non_negative("ste.world.position_noise", position_noise, 100.0, "m",
                     "0 is an exact position; seed 000's GPS (Eq. 4.3) is 1.08 m");
  check_non_negative("ste.world.odometry_drift", odometry_drift, 1.0, "m per sqrt(m)",
                     "0 records the true position");
  check_non_negative("ste.world.rotor_disc", rotor_disc, 10.0, "m",
                     "0 reads at a point; seed 000's rotor disturbance is 0.5 m");
}

}  // namespace plumekit::world
