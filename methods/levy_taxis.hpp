#pragma once
// Adaptive Lévy taxis (ALT; seed 004 ch. 16, Emery et al. 2017): a random walk whose move lengths
// follow a power law and whose turns follow a wrapped Cauchy distribution about a bias (upwind),
// with both adapted at every stop to the change of the gas reading since the last stop: a strong
// change gives a long, straight move (exploitation), none a short move in a random direction
// (exploration). Like the plume trackers it reads only its observations and never knows the
// source; the runner ends a run when the robot comes within the success radius of the source
// (seed 004 ch. 15: 0.5 m), and scores where it ends.
#include <cstdint>
#include <optional>
#include <random>
#include <string>

#include "methods/method.hpp"

namespace plumekit::methods {

struct LevyTaxisOptions {
  // Move lengths, m: L_min of Eq. 16.1, and the longest move (Fig. 16.1's moves run from 0.1 to
  // 2 m; the power law has no end, so longer draws are cut to it).
  double min_move = 0.1, max_move = 2.0;
  // The power law's exponent mu (1 < mu <= 3) and the turns' concentration gamma (0 <= gamma <= 1)
  // range between these as the gas changes (Figs. 16.1 and 16.2).
  double mu_min = 1.1, mu_max = 2.9;
  double gamma_min = 0.0, gamma_max = 1.0;
  // theta of Eqs. 16.3: a change of the stop's mean reading (concentration units) from which the
  // walk is all exploitation. Not in the thesis; 50, the trackers' detection threshold: on the
  // benchmark's open-field maps (docs/methods.md) 10 to 60 reached the source about equally
  // often and 150 half as often, its short exploring moves using up the budget.
  double gradient_threshold = 50.0;
  int max_steps = 300;  // stops before stopped_by() says "max_samples"

  // OptionError naming the field ("levy.min_move", ...).
  void validate() const;
};

// Eq. 16.1: M = L_min u^(1 / (1 - mu)) for u in (0, 1], cut to max_move. P(M > x) = (x /
// L_min)^(1 - mu) for L_min <= x < max_move.
double levy_move_length(double u, double mu, double min_move, double max_move);
// Eq. 16.2 without its bias: 2 atan((1 - gamma) / (1 + gamma) tan(pi (u - 1/2))) for u in [0, 1],
// radians in [-pi, pi]: the inverse distribution function of a wrapped Cauchy of mean resultant
// length gamma (uniform for 0, a point at 0 for 1).
double wrapped_cauchy_turn(double u, double gamma);

// Eqs. 16.3: mu and gamma for a change `gradient` of the reading (|gradient| >= threshold:
// mu_min and gamma_max; 0: mu_max and gamma_min; linear between).
struct LevyShape {
  double mu, gamma;
};
LevyShape adapt_levy_shape(double gradient, const LevyTaxisOptions& options);

class AdaptiveLevyTaxis : public LocalizationMethod {
 public:
  AdaptiveLevyTaxis(const LevyTaxisOptions& options, std::uint64_t seed);
  std::string name() const override { return "levy-taxis"; }
  void observe(const Observation& o) override;
  // The move drawn at the last observation, from where the robot truly stands (odometry, as the
  // trackers: the position noise blurs what it knows, not its moves).
  Move next(Vec2 robot) override;
  std::optional<Vec2> estimate() const override { return std::nullopt; }
  std::string stopped_by() const override;

  // The last move's shape, bias (radians, arena frame) and drawn step, for tests and pictures.
  LevyShape shape() const { return shape_; }
  double bias() const { return bias_; }
  Vec2 step() const { return step_; }

 private:
  LevyTaxisOptions options_;
  std::mt19937_64 rng_;
  std::optional<double> previous_gas_;
  double upwind_ = 3.141592653589793;  // radians; before any wind: -x
  LevyShape shape_{0.0, 0.0};
  double bias_ = 0.0;
  Vec2 step_;
  int stops_ = 0;
};

}  // namespace plumekit::methods
