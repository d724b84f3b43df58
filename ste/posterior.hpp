#pragma once
// The posterior over a plume model's parameters and what STE reads from it,
// and the estimator interface the localization loop drives.
//
// Likelihood (thesis eq. 7.5): P(D|m) ~ exp(-1/2 sum_i (D_i - C_i(m))^2 / (sigma_M^2 + sigma_D^2)),
// optionally with model errors that grow with the prediction (sigma_rel) and with
// the predicted std S_i(m) of the readings (sigma_std): then each sample's variance
// is sigma_M^2 + sigma_D^2 + (sigma_rel C_i(m))^2 + (sigma_std S_i(m))^2, and the
// Gaussian's normalisation, which then depends on m, enters the likelihood.
// Prior: uniform inside the parameter bounds, zero where the source would be
// inside an obstacle.
#include <cmath>
#include <memory>
#include <vector>

#include "core/geometry.hpp"
#include "core/grid.hpp"
#include "map/map.hpp"

namespace plumekit::ste {

struct LikelihoodOptions {
  double sigma_m = 30.0;  // model error, dataset units (thesis, simulation)
  double sigma_d = 0.0;   // measurement error (thesis: 0 in simulation, 125 in the wind tunnel)
  // Model error relative to the predicted concentration (0: the thesis's constant error). A
  // plume's 5 s mean scatters, and a CNN errs, in proportion to the concentration itself.
  double sigma_rel = 0.0;
  // Model error in units of the model's own predicted std of the readings at the sample point
  // (0: none). Only the surrogate predicts that std (its second output). A 5 s mean departs from
  // the long-run mean most, and the CNN errs most, where the plume is intermittent.
  double sigma_std = 0.0;
  // The variance of a sample whose predicted value is `predicted` and whose readings are
  // predicted to scatter by `spread` (std).
  double variance(double predicted = 0.0, double spread = 0.0) const {
    const double r = sigma_rel * predicted, q = sigma_std * spread;
    return sigma_m * sigma_m + sigma_d * sigma_d + r * r + q * q;
  }
  // Whether the variance depends on the hypothesis, so that the Gaussian's normalisation enters
  // the likelihood.
  bool variance_varies() const { return sigma_rel > 0.0 || sigma_std > 0.0; }
  // -1/2 ((value - predicted)^2 / variance + log variance): one sample's log-likelihood, up to a
  // constant. The log term is a constant, and so left out, unless the variance varies.
  double log_likelihood(double value, double predicted, double spread = 0.0) const {
    const double var = variance(predicted, spread), d = value - predicted;
    return -0.5 * (d * d / var + (variance_varies() ? std::log(var) : 0.0));
  }
  // OptionError naming the field ("ste.likelihood.sigma_m", ...) unless every sigma is finite,
  // >= 0 and within its bound, and sigma_m and sigma_d are not both 0; ste/options.cpp.
  void validate() const;
};

// The (x, y) bins of the thesis code: 0.5 m in x, 0.2 m in y. The entropy
// (and so the stopping rule) is measured on them whatever the estimator's own
// resolution, so the 2 % threshold means the same for every plume model.
struct BinOptions {
  double x = 0.5, y = 0.2;
  // OptionError naming the field (docs/methods.md, "Options"); ste/options.cpp.
  void validate() const;
};
GridShape make_bins(const Map& map, const BinOptions& bins);

struct Posterior {
  std::vector<double> expected;  // expected value of every parameter (the declared estimate)
  Vec2 map;                      // maximum a posteriori source position (navigation)
  // The (x, y) marginal on the estimator's own grid (sums to 1).
  Grid<double> marginal;
  double entropy = 0.0;      // nats, of the marginal aggregated on the bins
  double max_entropy = 0.0;  // log of the number of bins the prior reaches
  // The posterior's mass on sources that the samples so far could tell from no source at all:
  // those whose predicted readings at the samples add up to at least kSeenSigmas standard
  // deviations (sum_i C_i(m)^2 / var_i >= kSeenSigmas^2). A source whose plume reaches none of the
  // samples is unseen; the stopping rule does not declare one (localizer.hpp). 1 when the
  // estimator cannot tell (MH).
  double seen_mass = 1.0;
  static constexpr double kSeenSigmas = 3.0;
  Vec2 expected_source() const { return {expected.at(0), expected.at(1)}; }
};

// InputError unless 0 < weight <= 1: what Estimator::add_partial takes.
void check_weight(double weight);

// Aggregates a marginal onto bins (by cell centre) and returns its entropy in nats.
double entropy_on_bins(const Grid<double>& marginal, const GridShape& bins);

class Estimator {
 public:
  virtual ~Estimator() = default;
  // A sample: the mean concentration measured at p.
  virtual void add(Vec2 p, double value) = 0;
  // A reading that counts as `weight` (0 < weight <= 1) of a sample: the mean of a stretch of
  // readings taken on the way, shorter than a stop (Mission::add). Its log-likelihood is the
  // sample's times `weight` (a tempered likelihood: the readings along a path are no more
  // independent of one another than a stop's are, so a second of them counts as a second of a
  // stop). Not counted in samples(), which counts stops.
  virtual void add_partial(Vec2 p, double value, double weight) = 0;
  virtual int samples() const = 0;
  // The posterior given all samples so far.
  virtual Posterior posterior() = 0;
  // A copy holding the same samples (and, for MH, the same chain and random state): a team robot
  // adds virtual samples to one to plan with (run/team.hpp) and keeps its own unchanged.
  virtual std::unique_ptr<Estimator> clone() const = 0;
  // The mean reading at p that the current belief predicts: the model's at the expected
  // parameters (what the thesis's KL reward predicts; its ch. 13 virtual samples).
  virtual double predicted_reading(Vec2 p, const Posterior& current) const = 0;
  // The navigation reward (thesis eq. 7.6): KL(P || Q), where P is the current
  // posterior and Q the one after a sample at p that reads what the model
  // predicts there for the current expected parameters.
  virtual double information_gain(Vec2 p, const Posterior& current) const = 0;
  // The expected information gain of a sample at p: the KL divergence from the current
  // posterior to the one after the sample, averaged over what the sample may read, i.e. over
  // sources drawn from the current posterior. Estimators that cannot afford it fall back to
  // information_gain().
  virtual double expected_information_gain(Vec2 p, const Posterior& current) const {
    return information_gain(p, current);
  }
  // The expected information gain at each of `points`, for one decision. max_cells > 0 lets the
  // estimator approximate within that many hypotheses per point (hundreds of goals over a floor);
  // 0 asks for the exact gains.
  virtual std::vector<double> expected_information_gains(const std::vector<Vec2>& points,
                                                         const Posterior& current,
                                                         int /*max_cells*/) const {
    std::vector<double> gains;
    for (const Vec2& p : points)
      gains.push_back(expected_information_gain(p, current));
    return gains;
  }
};

}  // namespace plumekit::ste
