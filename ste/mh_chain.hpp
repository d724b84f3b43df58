#pragma once
// The random-walk Metropolis-Hastings chain of thesis section 7.2, over any parameter vector with
// a box prior: one Gaussian proposal per parameter (std `proposal` times its prior range), the
// symmetric acceptance rule min(1, L_new / L_old). Shared by the 2-D estimator (mh_estimator.hpp)
// and the 3-D one (ste_3d.hpp), which differ only in their model and their bins.
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "core/random.hpp"
#include "ste/forward_model.hpp"

namespace plumekit::ste {

struct MhChain {
  std::vector<std::vector<double>> states;  // after burn-in, one per iteration
  std::vector<double> best;                 // the most probable state visited
  double acceptance = 0.0;
};

// Continues the chain from `state` (left at its last state) for `iterations` steps and keeps the
// states after `burn_in`. log_posterior(m) is -infinity outside the prior.
template <class LogPosterior>
MhChain run_mh_chain(std::vector<double>& state, const std::vector<Parameter>& parameters,
                     int iterations, int burn_in, double proposal, std::mt19937_64& rng,
                     const LogPosterior& log_posterior) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  NormalSampler normal;  // a fresh pair per chain, as the committed results were drawn
  double lp = log_posterior(state);
  std::vector<double> candidate(state.size());
  MhChain chain;
  chain.best = state;
  double best = lp;
  int accepted = 0;
  for (int it = 0; it < iterations; ++it) {
    for (std::size_t k = 0; k < state.size(); ++k)
      candidate[k] = state[k] + proposal * (parameters[k].hi - parameters[k].lo) * normal(rng);
    const double lq = log_posterior(candidate);
    if (lq > -kInf && std::log(uniform01(rng)) < lq - lp) {
      state = candidate;
      lp = lq;
      ++accepted;
      if (lp > best) best = lp, chain.best = state;
    }
    if (it >= burn_in) chain.states.push_back(state);
  }
  chain.acceptance = static_cast<double>(accepted) / iterations;
  return chain;
}

// The thesis's reward (eq. 7.6) on a chain: KL(P || Q) between the current binned posterior
// `current` (P, per bin) and Q, the chain's states reweighted by exp(log_weight(state)) (the
// likelihood of a virtual reading), binned by bin_of(state).
template <class LogWeight, class BinOf>
double kl_after_reweighting(const std::vector<std::vector<double>>& states,
                            const std::vector<double>& current, const LogWeight& log_weight,
                            const BinOf& bin_of) {
  if (states.empty()) return 0.0;
  std::vector<double> lw(states.size());
  double top = -std::numeric_limits<double>::infinity();
  for (std::size_t s = 0; s < states.size(); ++s) {
    lw[s] = log_weight(states[s]);
    top = std::max(top, lw[s]);
  }
  std::vector<double> q(current.size(), 0.0);
  double total = 0.0;
  for (std::size_t s = 0; s < states.size(); ++s) {
    const double w = std::exp(lw[s] - top);
    q[bin_of(states[s])] += w;
    total += w;
  }
  double kl = 0.0;
  for (std::size_t b = 0; b < q.size(); ++b) {
    const double pb = current[b];
    if (pb <= 0.0) continue;
    kl += pb * std::log(pb / (q[b] / total));
  }
  return std::max(0.0, kl);
}

}  // namespace plumekit::ste
