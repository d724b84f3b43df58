#include "world/tunnel_plume.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "core/option_check.hpp"

namespace plumekit::world {

namespace {

// Reflects v into [0, hi].
double reflect(double v, double hi) {
  if (v < 0.0) v = -v;
  if (v > hi) v = 2.0 * hi - v;
  return std::clamp(v, 0.0, hi);
}

}  // namespace

void Tunnel::validate() const {
  check_range("tunnel.length", length, 1.0, 200.0, "m", "seed 004's tunnel is 10 m");
  check_range("tunnel.width", width, 1.0, 50.0, "m", "seed 004's tunnel is 4 m");
  check_range("tunnel.height", height, 1.0, 20.0, "m", "seed 004's tunnel is 2 m");
  check_positive("tunnel.wind", speed, 10.0, "m/s", "seed 004 used 0.2 and 0.9 m/s");
}

FilamentOptions tunnel_filament_options() {
  FilamentOptions o;
  o.occlusion = false;
  o.unsteady_wind = false;
  o.release_per_second = 100.0;
  o.dt = 0.1;
  o.sigma_walk = 0.1;
  o.growth = 0.01;
  o.meander_speed = 0.05;
  o.max_radius = 1.0;
  // Filaments live 100 s at 0.2 m/s: the count settles after that.
  o.min_spinup = 20.0;
  o.max_spinup = 150.0;
  return o;
}

TunnelPlume::TunnelPlume(const Tunnel& tunnel, Vec3 source, const FilamentOptions& options,
                         std::uint64_t seed)
    : tunnel_(tunnel), source_(source), o_(options), rng_(seed) {
  tunnel.validate();
  o_.validate();
  if (o_.occlusion || o_.unsteady_wind || o_.source_radius > 0.0)
    throw OptionError("plume.world",
                      "the 3-D tunnel has no map: occlusion, the unsteady wind and a source disc "
                      "do not apply (use world::tunnel_filament_options())");
  if (!is_finite(source) || !tunnel.box().contains(source))
    throw InputError("tunnel plume: source (" + compact(source.x) + ", " + compact(source.y) +
                     ", " + compact(source.z) + ") is not inside the " + compact(tunnel.length) +
                     " x " + compact(tunnel.width) + " x " + compact(tunnel.height) + " m tunnel");
  mass_ = o_.release_rate / o_.release_per_second;
}

void TunnelPlume::step() {
  const double dt = o_.dt;
  const double walk = o_.sigma_walk * std::sqrt(dt);
  // Ornstein-Uhlenbeck meander, exact update over dt (as the 2-D model's).
  const double decay = std::exp(-dt / o_.meander_time);
  const double kick = o_.meander_speed * std::sqrt(1.0 - decay * decay);
  meander_.x = decay * meander_.x + kick * normal_(rng_);
  meander_.y = decay * meander_.y + kick * normal_(rng_);
  meander_.z = decay * meander_.z + kick * normal_(rng_);

  release_debt_ += o_.release_per_second * dt;
  while (release_debt_ >= 1.0) {
    filaments_.push_back({source_, o_.initial_radius * o_.initial_radius});
    release_debt_ -= 1.0;
  }
  const Vec3 w = wind();
  const double max_r2 = o_.max_radius * o_.max_radius;
  std::size_t kept = 0;
  for (std::size_t k = 0; k < filaments_.size(); ++k) {
    Filament3 f = filaments_[k];
    Vec3 p = f.position + dt * w;
    p.x += walk * normal_(rng_);
    p.y += walk * normal_(rng_);
    p.z += walk * normal_(rng_);
    if (p.x > tunnel_.length) continue;  // out through the outlet
    f.position = {reflect(p.x, tunnel_.length), reflect(p.y, tunnel_.width),
                  reflect(p.z, tunnel_.height)};
    f.radius2 += o_.growth * dt;
    if (f.radius2 > max_r2) continue;
    filaments_[kept++] = f;
  }
  filaments_.resize(kept);
  time_ += dt;
}

double TunnelPlume::concentration_at(Vec3 p) const {
  // Kernels summed out to cutoff * R, as in 2-D.
  double c = 0.0;
  const double cut2 = o_.cutoff * o_.cutoff;
  for (const Filament3& f : filaments_) {
    const Vec3 d = p - f.position;
    const double r2 = d.x * d.x + d.y * d.y + d.z * d.z;
    if (r2 > cut2 * f.radius2) continue;
    c += std::exp(-r2 / f.radius2) / (f.radius2 * std::sqrt(f.radius2));
  }
  return c * mass_ / (kPi * std::sqrt(kPi));
}

void TunnelPlume::concentration_on(const GridShape& g, Plane plane, double at,
                                   std::vector<float>& out) const {
  std::vector<double> c(g.size(), 0.0);
  const double cut2 = o_.cutoff * o_.cutoff;
  for (const Filament3& f : filaments_) {
    const double off = plane == Plane::Top ? f.position.z - at : f.position.y - at;
    const double reach2 = cut2 * f.radius2 - off * off;
    if (reach2 < 0.0) continue;
    // The cells whose centres lie within the filament's cut-off circle in the plane.
    const double reach = std::sqrt(reach2);
    const double u = f.position.x, v = plane == Plane::Top ? f.position.y : f.position.z;
    const int i0 = std::max(0, static_cast<int>(std::ceil((u - reach) / g.dx() - 0.5)));
    const int i1 = std::min(g.nx - 1, static_cast<int>(std::floor((u + reach) / g.dx() - 0.5)));
    const int j0 = std::max(0, static_cast<int>(std::ceil((v - reach) / g.dy() - 0.5)));
    const int j1 = std::min(g.ny - 1, static_cast<int>(std::floor((v + reach) / g.dy() - 0.5)));
    const double weight = 1.0 / (f.radius2 * std::sqrt(f.radius2));
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) {
        const Vec2 p = g.centre(i, j);
        const double r2 = (p.x - u) * (p.x - u) + (p.y - v) * (p.y - v) + off * off;
        if (r2 <= cut2 * f.radius2) c[g.index(i, j)] += std::exp(-r2 / f.radius2) * weight;
      }
  }
  const double scale = mass_ / (kPi * std::sqrt(kPi));
  out.resize(g.size());
  for (std::size_t k = 0; k < c.size(); ++k)
    out[k] = static_cast<float>(c[k] * scale);
}

}  // namespace plumekit::world
