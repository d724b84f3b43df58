#pragma once
// The filament plume model of Farrell et al. (2002), in 2-D: puffs
// ("filaments") are released at the source, advected by the local wind plus a
// spatially uniform meander (coloured noise), each takes its own Gaussian
// random walk, and each grows as dR^2/dt = gamma. A filament of mass q and
// size R contributes q / (pi R^2) exp(-r^2 / R^2) to the concentration.
//
// In a steady wind the long-time mean is an advection-diffusion plume with the
// equivalent diffusivity D_eq = sigma_walk^2 / 2 + gamma / 4 (+ about
// meander_speed^2 * meander_time from the meander); the fluctuations about it
// (the std) come from the meander and the finite number of filaments.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <mutex>
#include <random>
#include <string>
#include <vector>

#include "cfd/wind_field.hpp"
#include "core/grid.hpp"
#include "core/random.hpp"
#include "core/thread_pool.hpp"
#include "map/map.hpp"
#include "world/gas_sensor.hpp"
#include "world/line_of_sight.hpp"
#include "world/obstacle_cells.hpp"
#include "world/wind_fluctuation.hpp"

namespace plumekit::world {

// How the plume is computed (issue 45). Fast: filaments as arrays moved a block at a time, their
// walks drawn from counter-based normals, the unsteady wind's modes read sixteen lanes at once,
// sensors read through a spatial index of the filaments, threads where they pay. V1: the world
// before issue 45, bit for bit, kept for one release so that published numbers can be reproduced
// (--world faithful-v1, thesis-v1, neumann-v1; docs/world.md, "Worlds"). Both follow the same
// physics; tests/world/engine_equivalence_test.cpp shows it.
enum class PlumeEngine { Fast, V1 };
const char* to_string(PlumeEngine engine);
// OptionError "plume.engine" for a name other than fast or v1.
PlumeEngine parse_plume_engine(const std::string& name);

struct FilamentOptions {
  // Filaments released per second (Neumann used 500/s). Each carries
  // release_rate / release_per_second, so the rate leaves the expected mean
  // unchanged and only sets the sampling noise; 200/s keeps the 64x64 sensor
  // grid cheap (the thesis-scale dataset in ~20 min on 2 cores).
  double release_per_second = 200.0;
  // Release rate per metre of depth (concentration units * m^2/s), shared
  // with the advection-diffusion model so both give the same mean.
  double release_rate = 1000.0;
  double initial_radius = 0.1;  // m, R at release (a source of ~0.1 m)
  // Filaments leave from uniformly random points of a disc of this radius about the source
  // (seed 002 §5: a circular source of 0.2 m, its filaments spread over it); 0: all from the
  // source's point, drawing nothing (the other worlds' bytes).
  double source_radius = 0.0;
  // dR^2/dt, m^2/s: the filament's own growth (molecular + small-scale mixing).
  double growth = 0.08;
  // Random walk of each filament: displacement N(0, sigma_walk^2 dt) per axis.
  double sigma_walk = 0.245;  // m/sqrt(s); with growth 0.08 gives D_eq = 0.05 m^2/s
  // Meander: an Ornstein-Uhlenbeck velocity shared by all filaments (Farrell's
  // large-scale wind perturbation); it makes the plume intermittent.
  double meander_speed = 0.15;  // m/s, stationary std per axis
  double meander_time = 1.0;    // s, correlation time
  double dt = 0.05;             // s, integration step (5 cm at 1 m/s: one flow cell)
  // A filament whose R exceeds this is dropped: it is so dilute that it adds
  // nothing measurable, and it bounds the cost in recirculation zones.
  double max_radius = 1.5;
  // Statistically steady: the filament count, averaged over consecutive
  // windows of this length, changes by less than steady_tolerance, and at
  // least min_spinup seconds have passed; give up after max_spinup.
  double steady_window = 2.0;
  double steady_tolerance = 0.02;
  double min_spinup = 4.0;
  double max_spinup = 60.0;
  // Recording: sensors read every 1 / sample_rate s for record_s.
  double record_s = 5.0;
  double sample_rate = 10.0;
  // Kernels are summed out to this many R (exp(-9) = 1.2e-4 of the peak).
  double cutoff = 3.0;
  // The world's two ingredients of issue 18, both on by default (the faithful
  // world); set_world(o, "thesis") turns both off, which reproduces the
  // thesis-style world and its committed figures exactly.
  // Line of sight: a filament adds to a sensor only when no obstacle edge
  // cuts the segment between them, so gas stops at walls.
  bool occlusion = true;
  // Unsteady wind (issue 18; world/wind_fluctuation.hpp): the meander becomes a
  // field that varies in space, is divergence-free and fades to zero at walls
  // and obstacles, with std meander_speed per axis and correlation time
  // meander_time, wavelengths from meander_length to twice it, fading over
  // meander_wall_layer; the uniform meander is then off. Steady: the flow
  // plus that uniform meander, the thesis-style wind.
  bool unsteady_wind = true;
  double meander_length = 2.0;      // m
  double meander_wall_layer = 1.0;  // m
  PlumeEngine engine = PlumeEngine::Fast;
  // Threads of one plume's step (fast engine; 0: one per core). The plume does not depend on
  // it. 1 where plumes already run in parallel (evaluate, dataset generate).
  int threads = 1;

  double equivalent_diffusivity() const { return 0.5 * sigma_walk * sigma_walk + 0.25 * growth; }
  // A filament's age when it is dropped for being max_radius wide, s: (R^2 - R0^2) / growth,
  // 28 s with the defaults. The world's gas lives no longer.
  double lifetime_s() const {
    return (max_radius * max_radius - initial_radius * initial_radius) / growth;
  }

  // Throws OptionError naming the field ("plume.release_rate",
  // "plume.filaments_per_second", "plume.dt", ...) and its allowed range
  // (docs/design/dataset.md, "Options"). FilamentSimulation calls it.
  void validate() const;
  // Upper bound of the filaments alive at once (all released during the
  // longest spin-up and the recording, none dropped), for the memory guard.
  double max_filaments() const;
};

// The world presets (--world, docs/world.md, "Worlds"): "faithful" (the
// defaults: occlusion and the unsteady wind) or "thesis" (neither), which set only
// those two fields and the fast engine; each with "-v1" ("faithful-v1") sets the V1 engine
// instead; or "neumann", seed 000 §4.1's filaments in a laminar wind (no
// meander, 500 filaments/s of 0.2 m, sigma_p 0.1 m per 0.1 s step (dt 0.1 s), almost no growth,
// a spin-up of at least 100 s), released over a source disc of 0.2 m, for the seeds' 32 x 8 m
// tunnel (also "neumann-v1"). OptionError "plume.world" for another name.
void set_world(FilamentOptions& options, const std::string& name);

struct Filament {
  Vec2 position;
  double radius2;  // R^2
};

struct FilamentSummary {
  double spinup_s = 0.0;
  bool steady = false;  // false: stopped at max_spinup
  int filaments_at_end = 0;
  long long released = 0;
  long long rejected_moves = 0;  // moves into obstacles, not taken
  long long left_through_outlet = 0;
  long long dropped_too_wide = 0;
  double sensor_warmup_s = 0.0;  // a gas sensor's warm-up before the record
  double seconds = 0.0;          // wall time
};

class FilamentSimulation;

// The plume at one moment as the sensors read it: what a robot's gas sensor and anemometer see
// there then. FilamentSimulation::capture() fills one; a plume several robots share keeps a ring
// of them (world/shared_plume.hpp), so that each robot reads at its own pace. Reading is const
// and may run on several threads at once.
class PlumeFrame {
 public:
  double concentration_at(Vec2 p) const;    // the gas concentration at p
  Vec2 wind_at(Vec2 p) const;               // the wind that carries the gas at p
  long long step() const { return step_; }  // the plume's steps since it was made
  double time() const { return time_; }     // s since the release
  std::size_t filament_count() const { return x_.size(); }

 private:
  friend class FilamentSimulation;
  double concentration_fast(Vec2 p) const;
  // The kernels at p of filaments first..last - 1 (one bucket), those behind a `part` edge left
  // out.
  double bucket_sum(Vec2 p, int first, int last, const std::vector<Edge>& part) const;
  double concentration_v1(Vec2 p) const;

  const FilamentSimulation* sim_ = nullptr;
  long long step_ = -1;
  double time_ = 0.0;
  // The fast engine: the filaments by square bucket (a spatial index), in their order within
  // one. V1: the filaments in their order, as V1 summed them.
  double bucket_ = 0.5;  // m
  int nx_ = 0, ny_ = 0;
  std::vector<int> start_;          // per bucket, its first filament; nx * ny + 1
  std::vector<double> x_, y_, r2_;  // the filaments
  std::vector<double> max_r2_;      // per bucket
  double max_r2_all_ = 0.0;
  std::vector<double> amplitudes_;  // the unsteady wind's modes then
  Vec2 meander_;                    // the uniform meander then
};

// One plume, stepped in time. Used through simulate() for datasets; the
// class is public so tests can check each step.
class FilamentSimulation {
 public:
  // Validates the options and checks the filaments' memory against the limit
  // (core/memory_limit.hpp) before any is released.
  FilamentSimulation(const Map& map, const cfd::WindField& wind, Vec2 source,
                     const FilamentOptions& options, std::uint64_t seed);

  void step();  // advance by options.dt
  double time() const { return time_; }
  std::size_t filament_count() const { return x_.size(); }
  Filament filament(std::size_t k) const { return {{x_[k], y_[k]}, r2_[k]}; }
  std::vector<Filament> filaments() const;  // a copy, for tests and pictures
  const FilamentSummary& summary() const { return summary_; }
  // The meander velocity shared by all filaments now: the wind's large-scale
  // swing (zero with the unsteady wind, whose swing is in the field).
  Vec2 meander() const { return meander_; }
  // The wind that carries the gas at p now: the steady flow plus the meander,
  // or the unsteady field. What an anemometer there reads.
  Vec2 wind_at(Vec2 p) const {
    return wind_then(p, fluctuation_ ? fluctuation_->amplitudes().data() : nullptr, meander_);
  }
  bool unsteady() const { return fluctuation_ != nullptr; }
  // Adds the concentration at the cell centres of `shape` to `out`.
  void concentration(const GridShape& shape, std::vector<double>& out) const;
  // The concentration at one point (what a robot's sensor reads there now); may run on several
  // threads at once.
  double concentration_at(Vec2 p) const;
  // The plume now as sensors read it, into `frame` (its storage is reused).
  void capture(PlumeFrame& frame) const;

 private:
  bool free_at(Vec2 p) const;
  // What happens at the arena's walls and obstacles to a filament moving from `from` to `p`:
  // Kept (p is where it is now), Rejected (it stays at `from`) or Left (through an outlet).
  enum class Move { Kept, Rejected, Left };
  Move settle(Vec2 from, Vec2& p) const;
  void release_filaments(double dt);  // the filaments the source released over dt
  void add_filament(Vec2 p);
  // The fast engine (world/filament_step.cpp).
  void step_fast();
  Vec2 release_point_fast(std::uint64_t serial) const;
  void meander_fast(double dt);
  // The winds at filaments [begin, end) now, into wx[0 ..), wy[0 ..).
  void winds_fast(std::size_t begin, std::size_t end, double* wx, double* wy) const;
  // The fates of a run of moved filaments.
  struct Moved {
    std::size_t kept = 0;
    long long left = 0, rejected = 0, dropped = 0;
  };
  // Moves filaments [begin, end) with the step's key; the kept ones close up from `begin`.
  Moved move_fast(std::size_t begin, std::size_t end, std::uint64_t key);
  // Filament f moved from `from` towards p (settled as `move`): counts its fate in `fates` and,
  // when it stays (not out through an outlet, not grown past max_r2), writes it at `to` (<= f).
  // Both engines' steps end each filament's move with it.
  bool place(std::size_t f, std::size_t to, Vec2 from, Vec2 p, Move move, double growth,
             double max_r2, Moved& fates) {
    if (move == Move::Left) {
      ++fates.left;
      return false;
    }
    if (move == Move::Rejected) {
      ++fates.rejected;
      p = from;
    }
    const double r2 = r2_[f] + growth;
    if (r2 > max_r2) {
      ++fates.dropped;
      return false;
    }
    x_[to] = p.x;
    y_[to] = p.y;
    r2_[to] = r2;
    serial_[to] = serial_[f];
    return true;
  }
  // Keeps the first n filaments, and adds a step's fates to the summary.
  void close_up(std::size_t n, const Moved& fates);
  // The wind at p with the unsteady wind's amplitudes (null: the steady flow plus `meander`):
  // the plume's now, or a PlumeFrame's.
  Vec2 wind_then(Vec2 p, const double* amplitudes, Vec2 meander) const {
    return fluctuation_ ? fluctuation_->at(p, amplitudes) : wind_.at(p) + meander;
  }
  // The V1 engine (world/filament_model_v1.cpp): the world before issue 45, bit for bit.
  void step_v1();
  Vec2 release_point_v1();
  void advance_meander_v1(double dt);
  friend class PlumeFrame;
  // concentration() on sensor rows row_lo..row_hi only.
  void concentration_rows(const GridShape& shape, int row_lo, int row_hi,
                          std::vector<double>& out) const;
  // V1's (world/filament_model_v1.cpp): a mask per window, libm's exp.
  void concentration_rows_v1(const GridShape& shape, int row_lo, int row_hi,
                             std::vector<double>& out) const;

  const Map& map_;
  const cfd::WindField& wind_;
  Vec2 source_;
  FilamentOptions o_;
  std::uint64_t seed_;
  std::mt19937_64 rng_;   // V1
  NormalSampler normal_;  // V1; core/random.hpp: the same variates with any standard library
  // The filaments, as arrays: position, R^2 and (fast engine) the release number, which keys
  // its random draws.
  std::vector<double> x_, y_, r2_;
  std::vector<std::uint64_t> serial_;
  std::unique_ptr<ThreadPool> pool_;    // fast engine, with options.threads other than 1
  ObstacleCells obstacles_;             // free_at, per flow cell
  std::vector<std::uint8_t> clear_;     // V1: per flow cell, no obstacle within it (free_at)
  std::unique_ptr<LineOfSight> sight_;  // with options.occlusion only
  std::unique_ptr<world::FluctuatingWind> fluctuation_;  // with options.unsteady_wind only
  double time_ = 0.0;
  long long steps_ = 0;
  double release_debt_ = 0.0;
  Vec2 meander_;
  double mass_ = 0.0;  // per filament
  FilamentSummary summary_;
  // The plume now as sensors read it, captured by the first read after a step.
  mutable std::mutex now_lock_;
  mutable PlumeFrame now_;
};

// V1's free cells: per flow cell, no obstacle within its half-diagonal of its centre.
std::vector<std::uint8_t> clear_cells_v1(const Map& map, const GridShape& cells);

struct SensorRecord {
  Grid<double> mean, std;
  FilamentSummary summary;
};

// Steps `sim` until statistically steady (the criterion of FilamentOptions);
// returns false when it gave up at max_spinup. Used by simulate_filaments and
// by ste/'s simulated world, whose plume then keeps running.
// A template, so that the 3-D tunnel's plume (tunnel_plume.hpp) spins up by the same rule.
template <class Plume>
bool spin_up(Plume& sim, const FilamentOptions& options) {
  // Window means of the filament count until two consecutive ones agree.
  const int per_window =
      std::max(1, static_cast<int>(std::lround(options.steady_window / options.dt)));
  double previous = -1.0;
  while (sim.time() < options.max_spinup - 1e-9) {
    double sum = 0.0;
    for (int s = 0; s < per_window; ++s) {
      sim.step();
      sum += static_cast<double>(sim.filament_count());
    }
    const double mean = sum / per_window;
    if (previous > 0.0 && sim.time() >= options.min_spinup - 1e-9 &&
        std::abs(mean - previous) <= options.steady_tolerance * previous)
      return true;
    previous = mean;
  }
  return false;
}

// Spin up until statistically steady, then record the sensors at the cell
// centres of `sensors`; sensors inside obstacles read 0. With a gas sensor
// other than the ideal one, each static sensor is switched on at the end of
// the spin-up, settled on the concentration it is in, and reads the running
// plume for its settling time (at most kMaxSensorWarmup) before the record;
// the record is then what it reads.
constexpr double kMaxSensorWarmup = 60.0;  // s
// That warm-up, in seconds before frames are counted: 0 for the ideal sensor.
inline double sensor_warmup_s(const GasSensorModel& sensor) {
  return sensor.ideal() ? 0.0 : std::min(sensor.settling_s(), kMaxSensorWarmup);
}
SensorRecord simulate_filaments(const Map& map, const cfd::WindField& wind, Vec2 source,
                                const GridShape& sensors, const FilamentOptions& options,
                                std::uint64_t seed, const GasSensorModel& sensor = {});

}  // namespace plumekit::world
