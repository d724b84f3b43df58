#pragma once
// Metropolis-Hastings over any ForwardModel's parameters (thesis section 7.2):
// a Gaussian random-walk proposal, the chain's states binned on the (x, y)
// grid. Each posterior() continues the chain from where it stopped, with the
// samples added since, for `iterations` steps, and summarises the states after
// `burn_in`. Used for the 5-parameter Gaussian plume, where a grid over all
// parameters would be too large.
#include <cstdint>
#include <random>
#include <vector>

#include "ste/forward_model.hpp"
#include "ste/posterior.hpp"

namespace plumekit::ste {

struct MhOptions {
  int iterations = 4000;  // per decision step
  int burn_in = 1000;     // of those, not summarised
  // Proposal std per parameter, as a fraction of its prior range.
  double proposal = 0.05;
  // OptionError naming the field (docs/methods.md, "Options"); ste/options.cpp.
  void validate() const;
};

class MhEstimator final : public Estimator {
 public:
  MhEstimator(const ForwardModel& model, const Map& map, const LikelihoodOptions& likelihood,
              const GridShape& bins, const MhOptions& options, std::uint64_t seed);
  void add(Vec2 p, double value) override;
  void add_partial(Vec2 p, double value, double weight) override;
  int samples() const override { return samples_; }
  Posterior posterior() override;
  std::unique_ptr<Estimator> clone() const override { return std::make_unique<MhEstimator>(*this); }
  double predicted_reading(Vec2 p, const Posterior& current) const override;
  double information_gain(Vec2 p, const Posterior& current) const override;
  double acceptance() const { return acceptance_; }  // of the last chain

 private:
  double log_posterior(const std::vector<double>& m) const;
  int bin_of(double x, double y) const;

  const ForwardModel& model_;
  const Map& map_;
  LikelihoodOptions likelihood_;
  GridShape bins_;
  MhOptions options_;
  std::mt19937_64 rng_;
  std::vector<Vec2> points_;
  std::vector<double> values_;
  std::vector<double> weights_;  // 1 for a stop's sample, less for a partial one
  int samples_ = 0;              // the stops' samples
  std::vector<double> state_;
  std::vector<std::vector<double>> chain_;  // the summarised states of the last run
  double acceptance_ = 0.0;
  double max_entropy_ = 0.0;
};

}  // namespace plumekit::ste
