#include "world/gas_sensor.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "core/option_check.hpp"
#include "world/option_tables.hpp"

namespace plumekit::world {

namespace {

// Seed 004 gives the MiCS-5521's times to 90 % and back to 10 %; a first-order
// response takes tau ln 10 for either.
const double kLn10 = std::log(10.0);

const std::vector<std::pair<std::string, GasSensorModel>>& presets() {
  static const std::vector<std::pair<std::string, GasSensorModel>> all = {
      {"ideal", {}},
      // Seed 000, Table 4.1: fitted rise and decay constants and dead times.
      {"catalytic", {7.0126, 0.0, 1.0, 2.8862, 5.0, 4.0, 0.0}},
      {"electrochemical", {16.1812, 0.0, 1.0, 14.2792, 10.0, 7.0, 0.0}},
      {"infrared", {2.4958, 42.5273, 0.8312, 4.1862, 4.0, 4.0, 0.0}},
      {"mox-fast", {0.13 / kLn10, 0.0, 1.0, 0.41 / kLn10, 0.0, 0.0, 0.0}},
  };
  return all;
}

// One reading interval of a first-order response towards u; tau 0 jumps.
double relax(double x, double u, double tau, double dt) {
  return tau > 0.0 ? u + (x - u) * std::exp(-dt / tau) : u;
}

}  // namespace

const OptionTable<GasSensorModel>& gas_sensor_option_table() {
  using O = GasSensorModel;
  static const OptionTable<O> table{
      "Gas sensor (world::GasSensorModel; --gas-sensor picks a preset)",
      {{"sensor.rise_s", "", &O::rise_s, non_negative(1e4, "s"),
        "Rise time constant (tau_r; tau_IR1 for infrared), s", "0 is an instantaneous rise"},
       {"sensor.rise_slow_s", "", &O::rise_slow_s, non_negative(1e4, "s"),
        "Slow part of an infrared rise (tau_IR2), s", "0 when the rise has one part"},
       {"sensor.fast_share", "", &O::fast_share, real_range(0.0, 1.0, ""),
        "Share of the rise with rise_s (eta)", "1 when the rise has one part"},
       {"sensor.decay_s", "", &O::decay_s, non_negative(1e4, "s"), "Decay time constant, s",
        "0 is an instantaneous decay"},
       {"sensor.dead_rise_s", "", &O::dead_rise_s, non_negative(1e4, "s"),
        "The reading starts to rise this long after the gas, s"},
       {"sensor.dead_decay_s", "", &O::dead_decay_s, non_negative(1e4, "s"),
        "The reading starts to fall this long after the gas goes, s"},
       {"sensor.baseline", "", &O::baseline, real_range(-1e9, 1e9, "concentration units"),
        "Added to every reading, concentration units (--baseline)"}}};
  return table;
}

void GasSensorModel::validate() const {
  plumekit::validate(gas_sensor_option_table(), *this);
}

GasSensorModel gas_sensor_preset(const std::string& name) {
  for (const auto& [key, model] : presets())
    if (key == name) {
      GasSensorModel named = model;
      named.name = key;
      return named;
    }
  std::string known;
  for (const std::string& k : gas_sensor_preset_names())
    known += (known.empty() ? "" : ", ") + k;
  throw OptionError("sensor.gas", "unknown gas sensor '" + name + "'; use one of " + known);
}

std::vector<std::string> gas_sensor_preset_names() {
  std::vector<std::string> names;
  for (const auto& entry : presets())
    names.push_back(entry.first);
  return names;
}

GasSensor::GasSensor(const GasSensorModel& model, double dt) : model_(model), dt_(dt) {
  model_.validate();
  check_positive("sensor.dt", dt, 1e4, "s", "one reading interval");
  rise_delay_ = static_cast<int>(std::lround(model_.dead_rise_s / dt));
  decay_delay_ = static_cast<int>(std::lround(model_.dead_decay_s / dt));
}

double GasSensorModel::settling_s() const {
  return std::max(dead_rise_s + 5.0 * std::max(rise_s, rise_slow_s), dead_decay_s + 5.0 * decay_s);
}

double GasSensorModel::mean_delay_s() const {
  const double rise = dead_rise_s + fast_share * rise_s + (1.0 - fast_share) * rise_slow_s;
  return 0.5 * (rise + dead_decay_s + decay_s);
}

void GasSensor::settle(double concentration) {
  inputs_.assign(static_cast<std::size_t>(std::max(rise_delay_, decay_delay_)) + 1, concentration);
  fast_ = slow_ = concentration;
}

double GasSensor::delayed(int steps) const {
  return steps < static_cast<int>(inputs_.size()) ? inputs_[static_cast<std::size_t>(steps)] : 0.0;
}

double GasSensor::read(double concentration) {
  if (model_.ideal()) return concentration + model_.baseline;
  inputs_.push_front(concentration);
  const std::size_t keep = static_cast<std::size_t>(std::max(rise_delay_, decay_delay_)) + 1;
  while (inputs_.size() > keep)
    inputs_.pop_back();
  const double up = delayed(rise_delay_), down = delayed(decay_delay_);
  const double eta = model_.fast_share;
  // Each part rises towards the gas delayed by the rise dead time when that is
  // above it, or decays towards the gas delayed by the decay dead time when
  // that is below; when both hold, the input with the shorter delay is the
  // newer news (gas gone 4 s ago outweighs gas present 5 s ago). Otherwise
  // it holds: the thesis's plateau.
  const bool newer_is_rise = rise_delay_ <= decay_delay_;
  auto step = [&](double x, double tau_rise) {
    const bool rise = up > x, fall = down < x;
    if (rise && (!fall || newer_is_rise)) return relax(x, up, tau_rise, dt_);
    if (fall) return relax(x, down, model_.decay_s, dt_);
    return x;
  };
  fast_ = step(fast_, model_.rise_s);
  if (eta < 1.0) slow_ = step(slow_, model_.rise_slow_s);
  return eta * fast_ + (1.0 - eta) * slow_ + model_.baseline;
}

}  // namespace plumekit::world
