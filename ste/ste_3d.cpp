#include "ste/ste_3d.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "core/option_check.hpp"
#include "core/random.hpp"
#include "ste/mh_chain.hpp"
#include "ste/option_tables.hpp"

namespace plumekit::ste {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();

int bins_along(double extent, double bin) {
  return std::max(1, static_cast<int>(std::ceil(extent / bin - 1e-9)));
}

}  // namespace

const OptionTable<Ste3dOptions>& ste3d_option_table() {
  using O = Ste3dOptions;
  static const OptionTable<O> table{
      "Tunnel STE, 3-D (ste::Ste3dOptions; its likelihood, MH and bounds as above)",
      {{"tunnel.ste.bin_x", "", &O::bin_x, positive(10.0, "m"), "Entropy bin length in x, m"},
       {"tunnel.ste.bin_y", "", &O::bin_y, positive(10.0, "m"), "Entropy bin length in y, m"},
       {"tunnel.ste.bin_z", "", &O::bin_z, positive(10.0, "m"), "Entropy bin length in z, m"},
       {"tunnel.ste.step", "", &O::step, positive(10.0, "m"), "The candidate moves' length, m"},
       {"tunnel.ste.alpha", "", &O::alpha, real_range(0.0, 1.0, ""),
        "Weight of the KL move against the MAP move"},
       {"tunnel.ste.entropy_fraction", "", &O::entropy_fraction, non_negative(1.0, ""),
        "Stop below this share of the maximum entropy"},
       {"tunnel.ste.max_samples", "--max-samples", &O::max_samples, count_range(1, 100'000),
        "ste-3d: samples before it declares without certainty"}}};
  return table;
}

void Ste3dOptions::validate() const {
  likelihood.validate();
  mh.validate();
  bounds.validate();
  plumekit::validate(ste3d_option_table(), *this);
}

double gaussian_plume_3d(const double* m, Vec3 p, double speed) {
  const double d = p.x - m[0];
  if (d <= 0.0) return 0.0;
  const double dy = p.y - m[1], dz = p.z - m[2];
  const double sigma = m[4] * d + m[5];
  const double s2 = sigma * sigma;
  return m[3] / (2.0 * kPi * speed * s2) * std::exp(-(dy * dy + dz * dz) / (2.0 * s2));
}

Ste3dEstimator::Ste3dEstimator(const Box3& tunnel, const Ste3dOptions& options, std::uint64_t seed)
    : tunnel_(tunnel),
      options_(options),
      nx_(bins_along(tunnel.hi.x - tunnel.lo.x, options.bin_x)),
      ny_(bins_along(tunnel.hi.y - tunnel.lo.y, options.bin_y)),
      nz_(bins_along(tunnel.hi.z - tunnel.lo.z, options.bin_z)),
      rng_(seed) {
  options.validate();
  const GaussianPlumeBounds& b = options.bounds;
  parameters_ = {{"x", tunnel.lo.x, tunnel.hi.x}, {"y", tunnel.lo.y, tunnel.hi.y},
                 {"z", tunnel.lo.z, tunnel.hi.z}, {"Q", 0.0, b.q_max},
                 {"a", b.a_min, b.a_max},         {"b", b.b_min, b.b_max}};
  for (const Parameter& p : parameters_)
    state_.push_back(0.5 * (p.lo + p.hi));
}

void Ste3dEstimator::add(Vec3 p, double value, double wind_speed) {
  if (!is_finite(p) || !std::isfinite(value) || !std::isfinite(wind_speed) || value < 0.0 ||
      wind_speed <= 0.0)
    throw InputError("3-D STE: a sample that is not finite, a negative reading or no wind");
  points_.push_back(p);
  values_.push_back(value);
  speeds_.push_back(wind_speed);
}

double Ste3dEstimator::speed() const {
  double sum = 0.0;
  for (double s : speeds_)
    sum += s;
  return sum / speeds_.size();
}

int Ste3dEstimator::bin_of(const std::vector<double>& m) const {
  const int i = std::clamp(static_cast<int>((m[0] - tunnel_.lo.x) / options_.bin_x), 0, nx_ - 1);
  const int j = std::clamp(static_cast<int>((m[1] - tunnel_.lo.y) / options_.bin_y), 0, ny_ - 1);
  const int k = std::clamp(static_cast<int>((m[2] - tunnel_.lo.z) / options_.bin_z), 0, nz_ - 1);
  return (k * ny_ + j) * nx_ + i;
}

double Ste3dEstimator::log_posterior(const std::vector<double>& m) const {
  for (std::size_t k = 0; k < m.size(); ++k)
    if (m[k] < parameters_[k].lo || m[k] > parameters_[k].hi) return -kInf;
  double l = 0.0;
  for (std::size_t i = 0; i < points_.size(); ++i)
    l +=
        options_.likelihood.log_likelihood(values_[i], gaussian_plume_3d(m.data(), points_[i], u_));
  return l;
}

Posterior3 Ste3dEstimator::posterior() {
  if (points_.empty()) throw std::logic_error("Ste3dEstimator: posterior() before any sample");
  u_ = speed();
  MhChain run =
      run_mh_chain(state_, parameters_, options_.mh.iterations, options_.mh.burn_in,
                   options_.mh.proposal, rng_, [this](const auto& m) { return log_posterior(m); });
  chain_ = std::move(run.states);
  Posterior3 post;
  post.expected.assign(state_.size(), 0.0);
  post.marginal.assign(bin_count(), 0.0);
  post.nx = nx_, post.ny = ny_, post.nz = nz_;
  const double w = 1.0 / chain_.size();
  for (const std::vector<double>& m : chain_) {
    for (std::size_t k = 0; k < m.size(); ++k)
      post.expected[k] += w * m[k];
    post.marginal[bin_of(m)] += w;
  }
  for (double p : post.marginal)
    if (p > 0.0) post.entropy -= p * std::log(p);
  post.max_entropy = std::log(static_cast<double>(bin_count()));
  post.map = {run.best[0], run.best[1], run.best[2]};
  return post;
}

double Ste3dEstimator::predicted_reading(Vec3 p, const Posterior3& current) const {
  return gaussian_plume_3d(current.expected.data(), p, u_);
}

double Ste3dEstimator::information_gain(Vec3 p, const Posterior3& current) const {
  const double predicted = predicted_reading(p, current);
  return kl_after_reweighting(
      chain_, current.marginal,
      [&](const std::vector<double>& m) {
        return options_.likelihood.log_likelihood(predicted, gaussian_plume_3d(m.data(), p, u_));
      },
      [&](const std::vector<double>& m) { return bin_of(m); });
}

Decision3 decide_3d(Vec3 robot, const Ste3dEstimator& estimator, const Posterior3& posterior,
                    const Box3& tunnel, const Ste3dOptions& options, double margin) {
  Decision3 d;
  const double s = options.step;
  const Vec3 moves[6] = {{s, 0, 0}, {-s, 0, 0}, {0, s, 0}, {0, -s, 0}, {0, 0, s}, {0, 0, -s}};
  const Box3 inner = tunnel.inset(margin);
  double best = -1.0;
  d.kld_target = robot;
  for (const Vec3& m : moves) {
    const Vec3 c = robot + m;
    if (!inner.contains(c)) continue;
    const double gain = estimator.information_gain(c, posterior);
    d.candidates.push_back(c);
    d.gains.push_back(gain);
    if (gain > best) best = gain, d.kld_target = c;
  }
  d.source_target = posterior.map;
  const Vec3 v =
      options.alpha * (d.kld_target - robot) + (1.0 - options.alpha) * (d.source_target - robot);
  d.goal = inner.clamp(robot + v);
  return d;
}

}  // namespace plumekit::ste
