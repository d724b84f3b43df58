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
      noise_rng_(stream_seed(seed, SteStream::SensorNoise)),
      gas_(options.sensor, 1.0 / options.sample_rate) {
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

namespace {

// The point `d` metres along a polyline (its end beyond its length).
Vec2 point_along(const std::vector<Vec2>& path, double d) {
  for (std::size_t k = 1; k < path.size(); ++k) {
    const double leg = norm(path[k] - path[k - 1]);
    if (d <= leg && leg > 0.0) return path[k - 1] + (d / leg) * (path[k] - path[k - 1]);
    d -= leg;
  }
  return path.back();
}

}  // namespace

void SimulatedWorld::travel(const std::vector<Vec2>& path, double metres) {
  const double seconds = metres / options_.speed;
  if (!gas_.has_memory() || path.size() < 2) {
    advance(seconds);
    return;
  }
  const double interval = 1.0 / options_.sample_rate;
  const int readings = static_cast<int>(std::floor(seconds / interval));
  for (int k = 1; k <= readings; ++k) {
    advance(interval);
    gas_.read(sim_.concentration_at(point_along(path, k * interval * options_.speed)));
  }
  advance(seconds - readings * interval);
}

double SimulatedWorld::sample(Vec2 p) {
  const int n =
      std::max(1, static_cast<int>(std::lround(options_.sample_s * options_.sample_rate)));
  NormalSampler noise;  // a fresh pair per sample, as the committed results were drawn
  double sum = 0.0;
  for (int k = 0; k < n; ++k) {
    if (k > 0) advance(1.0 / options_.sample_rate);
    double c = gas_.read(sim_.concentration_at(p));
    if (options_.noise > 0.0) c = std::max(0.0, c + normal(noise, noise_rng_, 0.0, options_.noise));
    sum += c;
  }
  advance(1.0 / options_.sample_rate);  // the last reading's interval
  return sum / n;
}

}  // namespace plumekit::ste
