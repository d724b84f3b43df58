#pragma once
// Exact evaluation of the posterior on every candidate source cell of a
// SourceTableModel: cheap for its two or three parameters, and free of the
// sampling noise of Metropolis-Hastings.
//
// Per cell k it keeps A_k = sum w_ik r_ik^2, B_k = sum w_ik r_ik D_i,
// C_k = sum w_ik D_i^2 and H_k = sum log(1 / w_ik) (r_ik: the cell's
// unit-release reading at sample i; w_ik = 1 / variance of that sample, which
// is the same for every cell unless sigma_rel or sigma_std > 0), so that the
// log-likelihood of a release scale s is -(C_k - 2 s B_k + s^2 A_k) / 2 - H_k / 2.
// With sigma_rel or sigma_std, the variance is taken at the prediction for the
// prior's mean scale, so that the scale still integrates in closed form.
// The scale is either fixed (the prior's bounds coincide) or marginalised in
// closed form over its uniform prior [lo, hi] (a Gaussian integral: erf).
#include <vector>

#include "ste/forward_model.hpp"
#include "ste/posterior.hpp"

namespace plumekit::ste {

class GridEstimator final : public Estimator {
 public:
  GridEstimator(const SourceTableModel& model, const LikelihoodOptions& likelihood,
                const GridShape& bins);
  void add(Vec2 p, double value) override;
  void add_partial(Vec2 p, double value, double weight) override;
  int samples() const override { return samples_; }
  Posterior posterior() override;
  std::unique_ptr<Estimator> clone() const override {
    return std::make_unique<GridEstimator>(*this);
  }
  double predicted_reading(Vec2 p, const Posterior& current) const override;
  double information_gain(Vec2 p, const Posterior& current) const override;
  // Averaged over `hypotheses` sources at evenly spaced quantiles of the posterior's cumulative
  // mass (deterministic), each reading its noise-free prediction at p at the expected scale.
  double expected_information_gain(Vec2 p, const Posterior& current) const override;
  static constexpr int hypotheses = 32;
  // The expected gains of a set of points. With max_cells > 0 (scoring hundreds of goals over a
  // floor), approximately: over at most max_cells cells, drawn from the posterior by systematic
  // resampling when it has more (each weighted by its share of the draws), and with the cells
  // whose plume does not reach a point merged into one. With 0, exactly (every cell with mass).
  std::vector<double> expected_information_gains(const std::vector<Vec2>& points,
                                                 const Posterior& current,
                                                 int max_cells) const override;
  // The cells an expected gain sums over, with their weights (the posterior's, or the draws').
  static std::vector<std::pair<std::size_t, double>> gain_support(const std::vector<double>& w,
                                                                  int max_cells);

  // The normalised log-likelihood of each cell for given sufficient statistics
  // (-inf where the prior is zero). Exposed for tests.
  struct Sums {
    std::vector<double> a, b, c, h;
  };
  std::vector<double> log_weights(const Sums& sums) const;

 private:
  const SourceTableModel& model_;
  LikelihoodOptions likelihood_;
  GridShape bins_;
  double scale_lo_, scale_hi_;
  Sums sums_;
  int samples_ = 0;
  // Adds a sample reading `value` where the cells read r and their readings scatter by `spread`
  // (unit release; spread empty: none), its log-likelihood times `weight`.
  void accumulate(Sums& sums, const std::vector<double>& r, const std::vector<double>& spread,
                  double value, double weight = 1.0) const;
  // The reading the expected parameters predict where the cells read r (unit release).
  double predicted_from(const std::vector<double>& r, const Posterior& current) const;
  // The model's predicted std of the readings at p, when the likelihood uses it.
  std::vector<double> spreads_at(Vec2 p) const;
  double max_entropy_ = 0.0;
};

}  // namespace plumekit::ste
