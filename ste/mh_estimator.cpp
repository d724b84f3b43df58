#include "ste/mh_estimator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "core/random.hpp"

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
}

double MhEstimator::log_posterior(const std::vector<double>& m) const {
  const std::vector<Parameter>& ps = model_.parameters();
  for (std::size_t k = 0; k < m.size(); ++k)
    if (m[k] < ps[k].lo || m[k] > ps[k].hi) return -kInf;
  if (!map_.is_free({m[0], m[1]})) return -kInf;
  double l = 0.0;
  for (std::size_t i = 0; i < points_.size(); ++i)
    l += likelihood_.log_likelihood(values_[i], model_.predict_at(m.data(), points_[i]));
  return l;
}

Posterior MhEstimator::posterior() {
  const std::vector<Parameter>& ps = model_.parameters();
  NormalSampler normal;  // a fresh pair per chain, as the committed results were drawn
  double lp = log_posterior(state_);
  std::vector<double> proposal(state_.size()), best_state = state_;
  double best = lp;
  chain_.clear();
  int accepted = 0;
  for (int it = 0; it < options_.iterations; ++it) {
    for (std::size_t k = 0; k < state_.size(); ++k)
      proposal[k] = state_[k] + options_.proposal * (ps[k].hi - ps[k].lo) * normal(rng_);
    const double lq = log_posterior(proposal);
    if (lq > -kInf && std::log(uniform01(rng_)) < lq - lp) {
      state_ = proposal;
      lp = lq;
      ++accepted;
      if (lp > best) best = lp, best_state = state_;
    }
    if (it >= options_.burn_in) chain_.push_back(state_);
  }
  acceptance_ = static_cast<double>(accepted) / options_.iterations;

  Posterior post;
  post.expected.assign(state_.size(), 0.0);
  post.marginal = Grid<double>(bins_, 0.0);
  const double w = 1.0 / chain_.size();
  for (const std::vector<double>& m : chain_) {
    for (std::size_t k = 0; k < m.size(); ++k)
      post.expected[k] += w * m[k];
    post.marginal.values[bin_of(m[0], m[1])] += w;
  }
  post.map = {best_state[0], best_state[1]};
  post.entropy = entropy_on_bins(post.marginal, bins_);
  post.max_entropy = max_entropy_;
  return post;
}

double MhEstimator::predicted_reading(Vec2 p, const Posterior& current) const {
  return model_.predict_at(current.expected.data(), p);
}

double MhEstimator::information_gain(Vec2 p, const Posterior& current) const {
  if (chain_.empty()) return 0.0;
  // Reweight the chain's states by the likelihood of the predicted reading.
  const double predicted = model_.predict_at(current.expected.data(), p);
  std::vector<double> lw(chain_.size());
  double top = -kInf;
  for (std::size_t s = 0; s < chain_.size(); ++s) {
    lw[s] = likelihood_.log_likelihood(predicted, model_.predict_at(chain_[s].data(), p));
    top = std::max(top, lw[s]);
  }
  std::vector<double> q(bins_.size(), 0.0);
  double total = 0.0;
  for (std::size_t s = 0; s < chain_.size(); ++s) {
    const double w = std::exp(lw[s] - top);
    q[bin_of(chain_[s][0], chain_[s][1])] += w;
    total += w;
  }
  double kl = 0.0;
  for (std::size_t b = 0; b < q.size(); ++b) {
    const double pb = current.marginal.values[b];
    if (pb <= 0.0) continue;
    kl += pb * std::log(pb / (q[b] / total));
  }
  return std::max(0.0, kl);
}

}  // namespace plumekit::ste
