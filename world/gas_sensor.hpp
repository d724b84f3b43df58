#pragma once
// A gas sensor's response (issue 18): what a real sensor reads while the
// true concentration at it changes. Neumann's model (seed 000, Eqs. 4.5-4.9,
// Table 4.1): after a dead time the reading rises towards the concentration
// with a first-order time constant (two, for infrared: a fast share eta and a
// slow rest), and after another dead time decays towards it with a third.
// Here it runs on a stream of readings, so it answers any history of
// concentrations, not only the step up and down the thesis fitted:
//
//   each component x moves towards its input u over one reading interval dt
//   as x <- u + (x - u) exp(-dt / tau), with tau = the rise constant when the
//   input delayed by the rise dead time is above x (u is that input), else
//   the decay constant with the input delayed by the decay dead time.
//
// The reading is eta x_fast + (1 - eta) x_slow + baseline. The ideal sensor
// (every constant 0) reads the concentration exactly.
#include <deque>
#include <string>
#include <utility>
#include <vector>

namespace plumekit::world {

struct GasSensorModel {
  double rise_s = 0.0;         // tau_r (tau_IR1 for infrared), s; 0: instantaneous
  double rise_slow_s = 0.0;    // tau_IR2, the slow part of an infrared rise, s
  double fast_share = 1.0;     // eta: the share of the rise with rise_s
  double decay_s = 0.0;        // tau_d, s
  double dead_rise_s = 0.0;    // t_s1: the reading starts to rise this long after the gas
  double dead_decay_s = 0.0;   // t_s2: ... and to fall this long after it goes
  double baseline = 0.0;       // added to every reading, concentration units
  std::string name = "ideal";  // the preset it came from, for reports

  bool ideal() const {
    return rise_s == 0.0 && rise_slow_s == 0.0 && decay_s == 0.0 && dead_rise_s == 0.0 &&
           dead_decay_s == 0.0;
  }
  // Throws OptionError naming the field ("sensor.rise_s", ...).
  void validate() const;
  // How long it takes to forget where it started: the longer dead time plus
  // five of the slowest time constant on that side (0 for the ideal sensor).
  double settling_s() const;
  // How late it reports what it meets, on average over rising and falling: each side's dead time
  // plus its mean time constant (a first-order stage's mean delay), s. STE places a reading taken
  // on the way where the robot was this long before (ste/passing_readings.hpp).
  double mean_delay_s() const;
};

// The presets by name: ideal; catalytic, electrochemical, infrared (seed 000,
// Table 4.1); mox-fast (seed 004's MiCS-5521: 0.13 s to 90 %, 0.41 s back to
// 10 %). OptionError naming sensor.gas and the known names otherwise.
GasSensorModel gas_sensor_preset(const std::string& name);
std::vector<std::string> gas_sensor_preset_names();

class GasSensor {
 public:
  // Readings every `dt` seconds; the sensor starts in clean air.
  GasSensor(const GasSensorModel& model, double dt);
  // Feeds the true concentration of the next reading interval and returns the reading.
  double read(double concentration);
  // As if it had been in `concentration` for ever: every stage at it, and the
  // dead times' memory full of it (a static sensor switched on in a plume
  // that has run for a while, before it settles on the plume's own history).
  void settle(double concentration);
  bool has_memory() const { return !model_.ideal(); }

 private:
  double delayed(int steps) const;  // the input `steps` readings ago (0 before the first)
  GasSensorModel model_;
  double dt_;
  int rise_delay_, decay_delay_;
  std::deque<double> inputs_;  // newest first, as many as the longer dead time needs
  double fast_ = 0.0, slow_ = 0.0;
};

}  // namespace plumekit::world
