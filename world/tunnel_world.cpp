#include "world/tunnel_world.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "world/random_streams.hpp"

namespace plumekit::world {

void validate_tunnel_world(const WorldOptions& options) {
  const WorldOptions defaults;
  const auto offered = [](bool at_default, const char* field) {
    if (!at_default)
      throw OptionError(std::string("tunnel.world.") + field,
                        "is not offered in the 3-D tunnel (its wind is uniform plus the meander; "
                        "positions come from the tunnel's tracking)");
  };
  offered(options.wind_direction_noise_deg == 0.0 && !options.wind_noise_from_table35,
          "wind_direction_noise");
  offered(options.wind_variance_noise_deg == 0.0, "wind_variance_noise");
  offered(options.odometry_drift == 0.0, "odometry_drift");
  offered(options.rotor_disc == 0.0, "rotor_disc");
  offered(options.position_noise_per_fix == defaults.position_noise_per_fix, "position_noise");
  options.validate();
}

TunnelWorld::TunnelWorld(const world::Tunnel& tunnel, Vec3 source, const WorldOptions& options,
                         std::uint64_t seed)
    : plume_(tunnel, source, options.filament, seed),
      source_(source),
      options_(options),
      gas_(options.sensor, 1.0 / options.sample_rate),
      noise_rng_(stream_seed(seed, SteStream::SensorNoise)),
      position_rng_(stream_seed(seed, SteStream::PositionNoise)) {
  validate_tunnel_world(options);
  world::spin_up(plume_, options.filament);
  spinup_s_ = plume_.time();
}

void TunnelWorld::advance(double seconds, Vec3 from, Vec3 to) {
  if (watcher_ && !started_) watcher_->frame(0, 0.0, plume_, from);
  started_ = true;
  debt_ += seconds;
  const double dt = options_.filament.dt;
  double gone = 0.0;
  while (debt_ >= dt - 1e-12) {
    plume_.step();
    debt_ -= dt;
    time_ += dt;
    gone += dt;
    ++steps_;
    if (watcher_ && steps_ % watcher_->every_steps() == 0) {
      const double f = seconds > 0.0 ? std::min(1.0, gone / seconds) : 1.0;
      watcher_->frame(steps_, time_, plume_, from + f * (to - from));
    }
  }
}

double TunnelWorld::read(Vec3 p) {
  double c = gas_.read(plume_.concentration_at(p));
  if (options_.noise > 0.0) c = std::max(0.0, c + normal(noise_, noise_rng_, 0.0, options_.noise));
  advance(1.0 / options_.sample_rate, p, p);
  return c;
}

Vec3 TunnelWorld::recorded(Vec3 p, double sd) {
  if (sd <= 0.0) return p;
  return {p.x + normal(position_, position_rng_, 0.0, sd),
          p.y + normal(position_, position_rng_, 0.0, sd),
          p.z + normal(position_, position_rng_, 0.0, sd)};
}

void TunnelWorld::travel(Vec3 from, Vec3 to) {
  const double seconds = norm(to - from) / options_.speed;
  if (!gas_.has_memory()) return advance(seconds, from, to);
  const double interval = 1.0 / options_.sample_rate;
  const int readings = static_cast<int>(std::floor(seconds / interval));
  for (int k = 1; k <= readings; ++k)
    read(from + (k * interval / seconds) * (to - from));
  const Vec3 last = from + (readings * interval / seconds) * (to - from);
  advance(seconds - readings * interval, last, to);
}

Reading3 TunnelWorld::readings(Vec3 from, Vec3 to, int n) {
  Reading3 r;
  for (int k = 1; k <= n; ++k) {
    r.wind = r.wind + plume_.wind();
    r.gas += read(from + (static_cast<double>(k) / n) * (to - from));
  }
  r.gas /= n;
  r.wind = (1.0 / n) * r.wind;
  r.position = recorded(to, options_.position_noise);
  return r;
}

Reading3 TunnelWorld::stop(Vec3 p) {
  return readings(
      p, p, std::max(1, static_cast<int>(std::lround(options_.sample_s * options_.sample_rate))));
}

Reading3 TunnelWorld::move(Vec3 from, Vec3 to, double speed) {
  const double interval = 1.0 / options_.sample_rate, seconds = norm(to - from) / speed;
  return readings(from, to, std::max(1, static_cast<int>(std::lround(seconds / interval))));
}

}  // namespace plumekit::world
