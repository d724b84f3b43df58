#include "ste/world.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "core/random.hpp"
#include "ste/seeds.hpp"

namespace plumekit::ste {

SimulatedWorld::SimulatedWorld(const Map& map, const cfd::WindField& wind, Vec2 source,
                               const WorldOptions& options, std::uint64_t seed)
    : source_(source),
      options_(options),
      sim_(map, wind, source, options.filament, seed),
      // An independent stream for the sensor, so noise never shifts the plume.
      noise_rng_(stream_seed(seed, SteStream::SensorNoise)) {
  options.validate();  // the filament simulation (sim_) has checked its own options already
  dataset::spin_up(sim_, options.filament);
  spinup_ = sim_.time();
}

void SimulatedWorld::advance(double seconds) {
  debt_ += seconds;
  const double dt = options_.filament.dt;
  while (debt_ >= dt - 1e-12) {
    sim_.step();
    debt_ -= dt;
  }
}

void SimulatedWorld::travel(double metres) {
  advance(metres / options_.speed);
}

double SimulatedWorld::sample(Vec2 p) {
  const int n =
      std::max(1, static_cast<int>(std::lround(options_.sample_s * options_.sample_rate)));
  NormalSampler noise;  // a fresh pair per sample, as the committed results were drawn
  double sum = 0.0;
  for (int k = 0; k < n; ++k) {
    if (k > 0) advance(1.0 / options_.sample_rate);
    double c = sim_.concentration_at(p);
    if (options_.noise > 0.0) c = std::max(0.0, c + normal(noise, noise_rng_, 0.0, options_.noise));
    sum += c;
  }
  advance(1.0 / options_.sample_rate);  // the last reading's interval
  return sum / n;
}

}  // namespace plumekit::ste
