#pragma once
// STE in the local framework (seed 004 ch. 12, Algorithm 1): no map of the environment and no
// positioning system. The robot knows its position only by odometry from its start (which drifts:
// WorldOptions::odometry_drift) and runs STE on a small local map, a square of `map_size` metres
// centred on where it opened it and aligned with the wind it measured there: the thesis's
// pseudo-Gaussian plume with Metropolis-Hastings (ste/gaussian_plume.hpp), bounded to the square,
// and the thesis's navigation inside it.
//
//   - A sample budget B_0 per local map (Eq. 12.1): each sample costs 1 when the entropy did not
//     fall (H_current / H_previous >= 1), else H_current / H_previous.
//   - When the budget is spent, the map moves: crosswind (left or right at random, by its size)
//     when nothing was sensed in it, else centred on the posterior's MAP; the robot travels to
//     the new centre and every sample is erased (odometry errors stay within one map).
//   - Obstacles are unknown: the robot drives straight (Move::straight); one in the way stops it
//     (its avoidance manoeuvre), and the goal it was sent to gets a measurement of 0, so that it
//     and its neighbours stop being worth sampling.
//   - It declares the posterior's expected source when the entropy falls below 2 % of its
//     maximum, or after max_samples.
#include <cstdint>
#include <memory>
#include <optional>
#include <random>
#include <vector>

#include "methods/method.hpp"
#include "planner/free_space.hpp"
#include "planner/planner.hpp"
#include "ste/gaussian_plume.hpp"
#include "ste/mh_estimator.hpp"
#include "ste/navigation.hpp"
#include "ste/posterior.hpp"

namespace plumekit::methods {

struct LocalFrameworkOptions {
  double map_size = 2.0;  // m, the local map's side (the thesis's 2 x 2 m)
  double budget = 7.0;    // B_0, samples per map when nothing is learnt (the thesis's 7)
  // A guard: the run declares after this many samples in all (--max-steps replaces it: two per
  // square metre of the arena, at least 50).
  int max_samples = 300;
  double sigma_m = 30.0;  // the likelihood's model error (the thesis's simulation value)
  double entropy_fraction = 0.02;
  ste::MhOptions mh;
  // Candidates: the thesis code's 3 x 3 lattice of 0.5 m moves, inside the local map.
  ste::NavigationOptions navigation{0.5, 1};
  // OptionError naming the field (local.map_size, ...).
  void validate() const;
};

// Eq. 12.1: the budget after a sample whose posterior has entropy `current`, the previous
// `previous` (> 0).
double next_budget(double budget, double current, double previous);

class LocalFrameworkSte : public methods::LocalizationMethod {
 public:
  LocalFrameworkSte(const LocalFrameworkOptions& options, std::uint64_t seed);
  ~LocalFrameworkSte() override;

  std::string name() const override { return "ste-local"; }
  void observe(const methods::Observation& o) override;
  // Where to sample next: a goal in the local map, or the next map's centre. Positions are the
  // robot's odometry; `robot` (where it truly is) only anchors the move it is sent on.
  methods::Move next(Vec2 robot) override;
  std::optional<Vec2> estimate() const override { return estimate_; }
  std::string stopped_by() const override { return stopped_by_; }

  double budget() const { return budget_; }
  int maps() const { return maps_; }  // local maps opened so far
  int map_samples() const;            // samples in the current local map

 private:
  struct Window;
  // Opens a local map centred at `centre` (odometry) aligned with `wind`.
  void open_map(Vec2 centre, Vec2 wind);

  LocalFrameworkOptions options_;
  std::mt19937_64 rng_;
  std::uint64_t seed_;
  std::unique_ptr<Window> window_;
  Vec2 odometry_;            // the robot's position by odometry at its last stop
  Vec2 last_goal_;           // where it was last sent (odometry)
  bool moving_map_ = false;  // the last move went to a new map's centre
  Vec2 wind_{1.0, 0.0};
  double budget_ = 0.0;
  double previous_entropy_ = -1.0;  // of this map's last posterior; < 0 before its first
  double sensed_ = 0.0;             // sum of this map's measurements
  int samples_ = 0, maps_ = 0;
  std::optional<Vec2> estimate_;
  std::string stopped_by_;
};

}  // namespace plumekit::methods
