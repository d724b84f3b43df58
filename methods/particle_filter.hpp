#pragma once
// The particle-filter gas source localization of Neumann et al. (seed 002 Sec. 4, seed 001
// Algorithm 1, seed 000 Ch. 6): particles are candidate source positions in the search rectangle
// F = [0, W] x [0, H]; each stop turns the gas reading into a binary detection z_t (an adaptive
// EMA threshold) and the stop's mean wind into a patch path envelope (PPE) C_t, the wedge upwind
// of the robot the sensed gas most likely came through; the weights are scaled by a six-case rule
// (in C_t / upwind of it / downwind of it, x z_t), resampled when the effective sample size drops,
// and the source estimate is the Maximum Neighbours Estimate (MNE).
//
// Angles: the seeds use compass azimuths of the direction the wind comes from; here every
// direction is a vector in the arena frame and Observation::wind points downwind, so the seeds'
// theta_u is the upwind unit `up` and their "theta_u - 90 deg" (left when facing upwind) is `up`
// turned counter-clockwise.
//
// Where the seeds are silent (all documented at the member that decides):
//   - readings below the lower detection limit count 0; c̄_0 = c_0 and z_0 = 0 (Eq. 3 needs c̄_-1);
//   - theta_C = 180 deg * S0 is floored at min_opening_deg for the weight factor only (S0 = 0
//     would zero every penalised weight; the rays keep the measured S0);
//   - a calm stop (|wind| < 1e-9 m/s) has no PPE: it updates the threshold, not the weights;
//   - a weight sum of 0 (or not finite) resets the weights to uniform;
//   - resampling is Carpenter et al.'s linear-time scheme (seed 000 App. F);
//   - plumekit's maps have obstacles: particles are only ever placed on free points
//     (SearchArea::is_free): initial and injected ones by rejection sampling, jittered ones by
//     redrawing the jitter (the resampled position itself when every redraw hits an obstacle).
#include <cstdint>
#include <optional>
#include <random>
#include <vector>

#include "core/geometry.hpp"
#include "core/random.hpp"
#include "methods/method.hpp"

namespace plumekit::methods {

struct ParticleFilterOptions {
  int particles = 1000;  // N
  // Penalties of Eq. 6 in (0, 1]: 1 is no penalty. The seeds' best are (0.4, 0.9) with the
  // predefined sweep (the default here) and (0.2, 0.8) with the pseudo-gradient tracker
  // (pf_options_for()).
  double alpha = 0.4;
  double beta = 0.9;
  double resample_fraction = 0.5;  // gamma: resample when N_eff < gamma N
  double injection = 0.1;          // delta: share of resampled particles drawn uniformly
  double jitter_variance = 0.1;    // m^2, per axis, on particles drawn by weight
  double mne_radius = 0.5;         // epsilon, m
  // th_c, concentration units: readings below count 0. The seeds used 0.05 of a field normalised
  // to 1; 50 is about that for a plumekit source of 1000 units/s, whose readings near the axis a
  // few metres downwind are in the hundreds to thousands.
  double detection_limit = 50.0;
  double ema_lambda = 0.5;  // lambda of the adaptive threshold (Eq. 4)
  // Floor of theta_C (deg) in the weight factor theta_C / 180 deg: the seeds require
  // theta_C in (0, 180] but a steady wind (S0 = 0) gives 0.
  double min_opening_deg = 1.0;

  // OptionError naming the field ("pf.alpha", ...) for a value out of range.
  void validate() const;
};

// The binary detection of Li et al. (seed 002 Eqs. 3-4): z_t = 1 when the reading c_t is above
// the exponential moving average c̄_{t-1} of the earlier readings, c̄_t = lambda c̄_{t-1} +
// (1 - lambda) c_t. Readings below the detection limit count 0 first. The first reading starts
// the average (c̄_0 = c_0) and is no detection (z_0 = 0): there is nothing yet to compare it with.
class AdaptiveThreshold {
 public:
  AdaptiveThreshold(double detection_limit, double lambda);
  // Reads c_t; returns z_t.
  bool update(double gas);
  double average() const { return average_; }  // c̄_t (0 before the first reading)
  int readings() const { return readings_; }

 private:
  double limit_, lambda_;
  double average_ = 0.0;
  int readings_ = 0;
};

// The PPE C_t of one stop (seed 000 Sec. 6.1.1.5, seed 002 Eq. 5): the triangle m0-r1-l1 (the
// robot's 0.5 m measurement radius, right angle at m0 downwind of the robot) and the rays from r1
// and l1 turned 90 deg * S0 off upwind, away from each other, clipped to the search rectangle.
struct PatchPathEnvelope {
  Vec2 position;  // where the robot stood
  Vec2 up;        // upwind unit (the seeds' mean wind azimuth theta_u)
  Vec2 m0, r1, l1;
  Vec2 right_ray, left_ray;  // unit directions of the rays from r1 and l1
  double opening_deg = 0.0;  // theta_C = 180 deg * S0, floored at min_opening_deg
  // C_t counter-clockwise, clipped to the search rectangle: m0, r1, I_r, the corners between,
  // I_l, l1 when the triangle lies inside it (the seeds' order; the first vertex may differ).
  Polygon polygon;

  // q in C_t (on the boundary counts), for q in the search rectangle.
  bool contains(Vec2 q) const;
  // q in S_t, the half-plane upwind of the line s through m0 across the wind (seed 000 Eq. 6.1).
  bool upwind_of_s(Vec2 q) const { return dot(q - m0, up) >= 0.0; }
};

// The PPE for a robot at `position` in a wind `wind` (downwind, non-zero) with circular variance
// `s0` in [0, 1], clipped to [0, width] x [0, height].
PatchPathEnvelope make_envelope(Vec2 position, Vec2 wind, double s0, double width, double height,
                                double min_opening_deg);

// The three classes of seed 000 Sec. 6.1.2: (a) in C_t, (b) outside C_t upwind of s (in S_t),
// (c) downwind of s.
enum class ParticleClass { Inside, Upwind, Downwind };
ParticleClass classify(const PatchPathEnvelope& envelope, Vec2 q);

// The factor of Eq. 6 (seed 002) / Eq. 1 (seed 001) a weight is multiplied by.
double weight_factor(ParticleClass c, bool detection, double alpha, double beta,
                     double opening_deg);

// Scales `weights` to sum 1. A sum of 0 or one that is not finite resets them to uniform 1/N and
// returns false (nothing can be learnt from weights that all vanished).
bool normalize_weights(std::vector<double>& weights);

// 1 / sum w^2 of normalised weights (Eq. 7 of seed 002).
double effective_sample_size(const std::vector<double>& weights);

// Carpenter et al.'s linear-time resampling (seed 000 App. F): `count` indices drawn with
// replacement with probability proportional to `weights` (>= 0, positive sum), in ascending order.
std::vector<int> carpenter_resample(const std::vector<double>& weights, int count,
                                    std::mt19937_64& rng);

// The Maximum Neighbours Estimate (seed 000 Sec. 6.1.4): the particle with the most other
// particles within `radius` (inclusive); ties go to the larger weight, then the lower index.
// O(N k) by a sweep over the particles sorted by x (k: particles within `radius` in x).
struct NeighbourCount {
  int index = -1;
  int neighbours = 0;
};
NeighbourCount maximum_neighbours(const std::vector<Vec2>& particles,
                                  const std::vector<double>& weights, double radius);
// Each particle's number of other particles within `radius`.
std::vector<int> neighbour_counts(const std::vector<Vec2>& particles, double radius);
// The MNE from neighbour_counts(): the most neighbours, then the larger weight, then the lower
// index.
NeighbourCount most_neighbours(const std::vector<int>& counts, const std::vector<double>& weights);

// What one update did.
struct FilterStep {
  bool detection = false;
  std::optional<PatchPathEnvelope> envelope;  // none for a calm stop
  double effective_size = 0.0;                // N_eff after normalisation, before resampling
  bool resampled = false;
  bool weights_reset = false;  // the zero-sum guard fired
};

class ParticleFilter {
 public:
  // N particles uniform over the free points of the area's rectangle, weights 1/N. Every random
  // choice comes from `seed`: the same seed gives the same particles, bit for bit.
  // InputError when no free point is found.
  ParticleFilter(const SearchArea& area, const ParticleFilterOptions& options, std::uint64_t seed);

  // One iteration of seed 001 Algorithm 1 from a stop: the detection z_t, the PPE, the weight
  // update, resampling when due, and the MNE. InputError for a position, reading, wind or wind
  // variance that is not finite.
  const FilterStep& update(const Observation& o);
  // The same from a PPE and a detection given directly.
  const FilterStep& update(const PatchPathEnvelope& envelope, bool detection);

  const std::vector<Vec2>& particles() const { return particles_; }
  const std::vector<double>& weights() const { return weights_; }
  // Replaces the particle set (a prior, or a hand-made case in tests); weights >= 0, same size.
  void set_particles(std::vector<Vec2> particles, std::vector<double> weights);

  Vec2 estimate() const { return particles_[mne_.index]; }  // the MNE
  NeighbourCount mne() const { return mne_; }
  const FilterStep& last_step() const { return step_; }
  const AdaptiveThreshold& threshold() const { return threshold_; }
  const ParticleFilterOptions& options() const { return options_; }
  int iterations() const { return iterations_; }

 private:
  void resample(const PatchPathEnvelope& envelope, bool detection);
  std::optional<Vec2> draw_injected(const PatchPathEnvelope& envelope, bool detection);
  std::optional<Vec2> draw_free();
  Vec2 jittered(Vec2 p);

  SearchArea area_;
  ParticleFilterOptions options_;
  std::mt19937_64 rng_;
  NormalSampler normal_;
  AdaptiveThreshold threshold_;
  std::vector<Vec2> particles_;
  std::vector<double> weights_;
  std::vector<int> counts_;  // neighbour counts, recomputed only when the particles move
  NeighbourCount mne_;
  FilterStep step_;
  int iterations_ = 0;
};

}  // namespace plumekit::methods
