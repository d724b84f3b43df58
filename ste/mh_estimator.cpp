#include "ste/mh_estimator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "core/random.hpp"
#include "ste/mh_chain.hpp"

namespace plumekit::ste {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
}

MhEstimator::MhEstimator(const ForwardModel& model, const Map& map,
                         const LikelihoodOptions& likelihood, const GridShape& bins,
                         const MhOptions& options, std::uint64_t seed)
    : model_(model),
      map_(map),
      likelihood_(likelihood),
      bins_(bins),
      options_(options),
      rng_(seed) {
  options.validate();
  likelihood.validate();
  if (likelihood.sigma_std > 0.0)
    throw OptionError("ste.likelihood.sigma_std",
                      "must be 0 here: Metropolis-Hastings models predict no std of the readings "
                      "(only the surrogate does)");
  // Start at the middle of every range, moved to a free point for (x, y).
  for (const Parameter& p : model.parameters())
    state_.push_back(0.5 * (p.lo + p.hi));
  for (int t = 0; t < 10000 && !map.is_free({state_[0], state_[1]}); ++t) {
    state_[0] = uniform(rng_, 0.0, map.width);
    state_[1] = uniform(rng_, 0.0, map.height);
  }
  // The bins a free point reaches (probed on a 5 cm lattice).
  std::vector<std::uint8_t> reached(bins.size(), 0);
  for (double y = 0.025; y < map.height; y += 0.05)
    for (double x = 0.025; x < map.width; x += 0.05)
      if (map.is_free({x, y})) reached[bin_of(x, y)] = 1;
  max_entropy_ = std::log(std::max<double>(1, std::count(reached.begin(), reached.end(), 1)));
}

int MhEstimator::bin_of(double x, double y) const {
  return static_cast<int>(
      bins_.index(std::clamp(static_cast<int>(x / bins_.dx()), 0, bins_.nx - 1),
                  std::clamp(static_cast<int>(y / bins_.dy()), 0, bins_.ny - 1)));
}

void MhEstimator::add(Vec2 p, double value) {
  points_.push_back(p);
  values_.push_back(value);
  weights_.push_back(1.0);
  ++samples_;
}

void MhEstimator::add_partial(Vec2 p, double value, double weight) {
  check_weight(weight);
  points_.push_back(p);
  values_.push_back(value);
  weights_.push_back(weight);
}

double MhEstimator::log_posterior(const std::vector<double>& m) const {
  const std::vector<Parameter>& ps = model_.parameters();
  for (std::size_t k = 0; k < m.size(); ++k)
    if (m[k] < ps[k].lo || m[k] > ps[k].hi) return -kInf;
  if (!map_.is_free({m[0], m[1]})) return -kInf;
  double l = 0.0;
  for (std::size_t i = 0; i < points_.size(); ++i)
    l += weights_[i] *
         likelihood_.log_likelihood(values_[i], model_.predict_at(m.data(), points_[i]));
  return l;
}

Posterior MhEstimator::posterior() {
  MhChain run =
      run_mh_chain(state_, model_.parameters(), options_.iterations, options_.burn_in,
                   options_.proposal, rng_, [this](const auto& m) { return log_posterior(m); });
  chain_ = std::move(run.states);
  acceptance_ = run.acceptance;

  Posterior post;
  post.expected.assign(state_.size(), 0.0);
  post.marginal = Grid<double>(bins_, 0.0);
  const double w = 1.0 / chain_.size();
  for (const std::vector<double>& m : chain_) {
    for (std::size_t k = 0; k < m.size(); ++k)
      post.expected[k] += w * m[k];
    post.marginal.values[bin_of(m[0], m[1])] += w;
  }
  post.map = {run.best[0], run.best[1]};
  post.entropy = entropy_on_bins(post.marginal, bins_);
  post.max_entropy = max_entropy_;
  return post;
}

double MhEstimator::predicted_reading(Vec2 p, const Posterior& current) const {
  return model_.predict_at(current.expected.data(), p);
}

double MhEstimator::information_gain(Vec2 p, const Posterior& current) const {
  // Reweight the chain's states by the likelihood of the predicted reading.
  const double predicted = model_.predict_at(current.expected.data(), p);
  return kl_after_reweighting(
      chain_, current.marginal.values,
      [&](const std::vector<double>& m) {
        return likelihood_.log_likelihood(predicted, model_.predict_at(m.data(), p));
      },
      [&](const std::vector<double>& m) { return bin_of(m[0], m[1]); });
}

}  // namespace plumekit::ste
