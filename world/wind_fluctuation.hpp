#pragma once
// Unsteady wind (issue 18): the steady flow plus a fluctuation that meanders
// in time and space, u(x, t) = u0(x) + sum_k a_k(t) phi_k(x).
//
// Each mode phi_k is the discrete curl of a streamfunction m(x) psi_k(x) on
// the flow grid's nodes: psi_k a plane wave (wavelength between L and 2L,
// random direction and phase) and m a wall factor that rises from 0 at every
// obstacle, wall and opening to 1 at `wall_layer` metres from them (a
// smoothstep). So every mode is exactly divergence-free on the MAC grid, moves
// no air through any wall, obstacle or opening (the openings' fluxes stay the
// steady flow's), is zero inside obstacles and fades to zero at walls. The
// amplitudes a_k are independent Ornstein-Uhlenbeck processes (coloured noise,
// as Farrell et al. 2002 drive their meander), scaled so that away from walls
// each velocity component fluctuates with std `intensity`.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <new>
#include <random>
#include <vector>

#include "cfd/wind_field.hpp"
#include "core/random.hpp"

namespace plumekit::world {

// Storage on 64-byte boundaries: one cell's modes (16 floats) then fill
// exactly one cache line instead of straddling two.
template <class T>
struct CacheLineAllocator {
  using value_type = T;
  static constexpr std::align_val_t kAlign{64};
  CacheLineAllocator() = default;
  template <class U>
  CacheLineAllocator(const CacheLineAllocator<U>&) {}
  T* allocate(std::size_t n) { return static_cast<T*>(::operator new(n * sizeof(T), kAlign)); }
  void deallocate(T* p, std::size_t) { ::operator delete(p, kAlign); }
  template <class U>
  bool operator==(const CacheLineAllocator<U>&) const {
    return true;
  }
  template <class U>
  bool operator!=(const CacheLineAllocator<U>&) const {
    return false;
  }
};

struct FluctuationOptions {
  double intensity = 0.15;    // m/s, std per axis away from walls
  double time_scale = 1.0;    // s, the amplitudes' correlation time
  double length_scale = 2.0;  // m, the shortest wavelength (the longest is twice it)
  double wall_layer = 1.0;    // m, where the wall factor reaches 1
};

class FluctuatingWind {
 public:
  // The modes' geometry and the first amplitudes (drawn from the stationary
  // distribution, so there is no transient) come from `seed`.
  FluctuatingWind(const cfd::WindField& steady, const FluctuationOptions& options,
                  std::uint64_t seed);

  // Advances the amplitudes by dt: the exact Ornstein-Uhlenbeck update.
  void advance(double dt);
  // The wind now: the steady flow plus the modes, each bilinear between cell
  // centres; zero inside obstacles and outside the arena, as WindField::at.
  Vec2 at(Vec2 p) const { return at(p, amplitude_.data()); }
  // The same with the modes' amplitudes of another moment (a PlumeFrame's, kModes of them).
  Vec2 at(Vec2 p, const double* amplitudes) const;
  // The modes at flow cell `cell` (row-major): u of modes 0..K-1, then v; what the fast plume
  // combines with amplitudes() once per cell and step (at() is their bilinear mean).
  const float* cell_modes(std::size_t cell) const { return &cell_modes_[cell * 2 * kModes]; }

  const cfd::WindField& steady() const { return steady_; }
  // Eight plane waves: enough directions for an isotropic swing, few enough
  // that reading the wind stays a small part of a filament's step.
  static constexpr int kModes = 8;
  int modes() const { return kModes; }
  // Mode k with unit amplitude, rebuilt on demand (for tests):
  // its face velocities are exactly divergence-free.
  cfd::WindField mode(int k) const;
  const std::vector<double>& amplitudes() const { return amplitude_; }

 private:
  // Independent modes of unit strength: K of them with std sigma / sqrt(K)
  // give std sigma per axis.
  double amplitude_sd() const { return o_.intensity / std::sqrt(double(kModes)); }

  struct Wave {
    double kx, ky, phase, scale;
  };

  const cfd::WindField& steady_;
  FluctuationOptions o_;
  std::vector<double> wall_factor_;  // per grid node
  std::vector<Wave> waves_;
  // Per cell, the modes' cell-centred u then v (2K values): what at() reads,
  // laid out so that one cell's are together. Float: they are shapes of unit
  // strength, and half the memory on building-sized grids.
  std::vector<float, CacheLineAllocator<float>> cell_modes_;
  static_assert(2 * kModes * sizeof(float) == 64, "one cell's modes are one cache line");
  std::vector<double> amplitude_;
  std::mt19937_64 rng_;
  NormalSampler normal_;
};

}  // namespace plumekit::world
