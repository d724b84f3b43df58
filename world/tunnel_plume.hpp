#pragma once
// Farrell's filament plume (filament_model.hpp) in 3-D, in a wind tunnel with a uniform wind: the
// setting of seed 004's 3-D chapters (ch. 11's 3-D STE, ch. 17's surge-spiral), which need no
// 3-D CFD. The tunnel is the box [0, length] x [0, width] x [0, height] with the wind blowing
// along +x (x downwind, y across, z up); filaments leave through the outlet (x = length) and are
// reflected by the other walls. Everything else is the 2-D model's, with the same options
// (world::FilamentOptions): release, random walk (now on three axes), growth dR^2/dt, the
// meander (an Ornstein-Uhlenbeck velocity on three axes shared by all filaments), the drop at
// max_radius and the spin-up rule. The options that need a map (occlusion, the unsteady wind
// field, a source disc) do not apply and must be off.
//
// A filament of mass q and size R adds q / (pi^(3/2) R^3) exp(-r^2 / R^2) to the concentration,
// so release_rate is here in concentration units * m^3/s. In the mean the plume is Arya's
// Gaussian (seed 004 Eq. 7.1) with sigma^2(d) = R0^2 / 2 + 2 D_eq d / u and Q = release_rate.
#include <cstdint>
#include <random>
#include <vector>

#include "core/geometry.hpp"
#include "core/grid.hpp"
#include "core/random.hpp"
#include "world/filament_model.hpp"

namespace plumekit::world {

struct Tunnel {
  double length = 10.0, width = 4.0, height = 2.0;  // m (seed 004 §5.1: 10 x 4 x 2 m)
  double speed = 0.9;                               // m/s, the uniform wind along +x
  Box3 box() const { return {{0.0, 0.0, 0.0}, {length, width, height}}; }
  // OptionError naming "tunnel.length", ... (at least 1 m each side, speed in (0, 10] m/s).
  void validate() const;
};

// The tunnel's filament options: the 2-D defaults made quasi-laminar, as seed 004 §4 describes its
// tunnel (a honeycomb straightener; Webots's wind laminar): a slow meander (0.05 m/s), a weak
// walk and growth (D_eq 0.0075 m^2/s), and filaments that live 100 s (max_radius 1 m), so gas
// reaches 20 m down the tunnel at 0.2 m/s; 100 filaments per second at dt 0.1 s keep a run's
// plume to a few seconds of computing. Occlusion and the unsteady wind off (no map).
FilamentOptions tunnel_filament_options();

struct Filament3 {
  Vec3 position;
  double radius2;  // R^2
};

class TunnelPlume {
 public:
  // OptionError for options that need a map (occlusion, unsteady_wind, source_radius) or for a
  // bad tunnel; InputError naming the source when it is not inside the tunnel.
  TunnelPlume(const Tunnel& tunnel, Vec3 source, const FilamentOptions& options,
              std::uint64_t seed);
  void step();  // advance by options.dt
  double time() const { return time_; }
  const std::vector<Filament3>& filaments() const { return filaments_; }
  std::size_t filament_count() const { return filaments_.size(); }
  // The wind that carries the gas now: the tunnel's plus the meander (what an anemometer reads).
  Vec3 wind() const { return Vec3{tunnel_.speed, 0.0, 0.0} + meander_; }
  // The concentration at p now.
  double concentration_at(Vec3 p) const;
  // The concentration now at the centres of g's cells in a plane: seen from above, cell (i, j)
  // is (x_i, y_j, at); from the side, (x_i, at, z_j). concentration_at's values, summed per
  // filament over the cells it reaches (a replay's frame: a few thousand cells).
  enum class Plane { Top, Side };
  void concentration_on(const GridShape& g, Plane plane, double at, std::vector<float>& out) const;
  const Tunnel& tunnel() const { return tunnel_; }
  const FilamentOptions& options() const { return o_; }

 private:
  Tunnel tunnel_;
  Vec3 source_;
  FilamentOptions o_;
  std::mt19937_64 rng_;
  NormalSampler normal_;
  std::vector<Filament3> filaments_;
  double time_ = 0.0, release_debt_ = 0.0, mass_ = 0.0;
  Vec3 meander_;
};

}  // namespace plumekit::world
