#pragma once
// Exact evaluation of the posterior on every candidate source cell of a
// SourceTableModel: cheap for its two or three parameters, and free of the
// sampling noise of Metropolis-Hastings.
//
// Per cell k it keeps A_k = sum r_ik^2 and B_k = sum r_ik D_i (r_ik: the
// cell's unit-release reading at sample i) and C = sum D_i^2, so that the
// log-likelihood of a release scale s is -(C - 2 s B_k + s^2 A_k) / (2 sigma^2).
// The scale is either fixed (the prior's bounds coincide) or marginalised in
// closed form over its uniform prior [lo, hi] (a Gaussian integral: erf).
#include <vector>

#include "ste/plume_model.hpp"
#include "ste/posterior.hpp"

namespace plumekit::ste {

class GridEstimator final : public Estimator {
 public:
  GridEstimator(const SourceTableModel& model, const LikelihoodOptions& likelihood,
                const GridShape& bins);
  void add(Vec2 p, double value) override;
  int samples() const override { return samples_; }
  Posterior posterior() override;
  double information_gain(Vec2 p, const Posterior& current) const override;

  // The normalised log-likelihood of each cell for given sufficient statistics
  // (-inf where the prior is zero). Exposed for tests.
  std::vector<double> log_weights(const std::vector<double>& a, const std::vector<double>& b,
                                  double c) const;

 private:
  const SourceTableModel& model_;
  LikelihoodOptions likelihood_;
  GridShape bins_;
  double scale_lo_, scale_hi_;
  std::vector<double> a_, b_;
  double c_ = 0.0;
  int samples_ = 0;
  double max_entropy_ = 0.0;
};

}  // namespace plumekit::ste
