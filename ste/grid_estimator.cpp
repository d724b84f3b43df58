#include "ste/grid_estimator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "core/geometry.hpp"
#include "core/option_check.hpp"

namespace plumekit::ste {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
const double kSqrt2 = std::sqrt(2.0);
const double kLogSqrtPi = 0.5 * std::log(kPi);

// log(erfc(x)), also where erfc underflows (its asymptotic series).
double log_erfc(double x) {
  if (x < 20.0) return std::log(std::erfc(x));
  return -x * x - std::log(x) - kLogSqrtPi + std::log1p(-0.5 / (x * x));
}

// log(Phi(b) - Phi(a)) for a < b, with Phi the standard normal CDF.
double log_phi_diff(double a, double b) {
  if (a >= 0.0) {  // both in the upper tail: 1 - Phi(a) - (1 - Phi(b))
    const double la = log_erfc(a / kSqrt2), lb = log_erfc(b / kSqrt2);
    return std::log(0.5) + la + std::log1p(-std::exp(lb - la));
  }
  if (b <= 0.0) return log_phi_diff(-b, -a);
  return std::log1p(-0.5 * std::erfc(b / kSqrt2) - 0.5 * std::erfc(-a / kSqrt2));
}

// log of the integral over s in [lo, hi] of exp(-(a s^2 - 2 b s + c) / (2 var)).
double log_marginal_scale(double a, double b, double c, double var, double lo, double hi) {
  if (a <= 1e-12 * var) return -c / (2.0 * var) + std::log(hi - lo);
  const double mu = b / a, sd = std::sqrt(var / a);
  return -(c - b * mu) / (2.0 * var) + std::log(std::sqrt(2.0 * kPi) * sd) +
         log_phi_diff((lo - mu) / sd, (hi - mu) / sd);
}

// Mean of the scale's posterior at one cell: a normal truncated to [lo, hi].
double mean_scale(double a, double b, double var, double lo, double hi) {
  if (a <= 1e-12 * var) return 0.5 * (lo + hi);
  const double mu = b / a, sd = std::sqrt(var / a);
  const double al = (lo - mu) / sd, be = (hi - mu) / sd;
  const double lz = log_phi_diff(al, be);
  const double log_pdf0 = -0.5 * std::log(2.0 * kPi);
  const double m =
      mu + sd * (std::exp(log_pdf0 - 0.5 * al * al - lz) - std::exp(log_pdf0 - 0.5 * be * be - lz));
  return std::clamp(std::isfinite(m) ? m : mu, lo, hi);
}

}  // namespace

GridEstimator::GridEstimator(const SourceTableModel& model, const LikelihoodOptions& likelihood,
                             const GridShape& bins)
    : model_(model), likelihood_(likelihood), bins_(bins) {
  const std::vector<Parameter>& p = model.parameters();
  scale_lo_ = p.size() > 2 ? p[2].lo : 1.0;
  scale_hi_ = p.size() > 2 ? p[2].hi : 1.0;
  if (!(scale_lo_ > 0.0) || scale_hi_ < scale_lo_)
    throw OptionError("ste.physics.scale_lo", "the release scale prior needs 0 < lo <= hi, got " +
                                                  compact(scale_lo_) + " and " +
                                                  compact(scale_hi_));
  likelihood.validate();
  if (likelihood.sigma_std > 0.0 && !model.has_spreads())
    throw OptionError("ste.likelihood.sigma_std",
                      "must be 0 here: the " + model.name() +
                          " model predicts no std of the readings (only the surrogate does)");
  for (std::vector<double>* v : {&sums_.a, &sums_.b, &sums_.c, &sums_.h})
    v->assign(model.candidates().size(), 0.0);
  // The largest entropy: every bin holding an allowed cell equally likely.
  Grid<double> uniform(model.candidates(), 0.0);
  for (std::size_t k = 0; k < uniform.values.size(); ++k)
    uniform.values[k] = model.allowed()[k];
  std::vector<std::uint8_t> reached(bins.size(), 0);
  const GridShape& g = model.candidates();
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i)
      if (model.allowed()[g.index(i, j)]) {
        const Vec2 c = g.centre(i, j);
        reached[bins.index(std::clamp(static_cast<int>(c.x / bins.dx()), 0, bins.nx - 1),
                           std::clamp(static_cast<int>(c.y / bins.dy()), 0, bins.ny - 1))] = 1;
      }
  const long n = std::count(reached.begin(), reached.end(), 1);
  if (n == 0) throw InputError("the map leaves no free cell for a source");
  max_entropy_ = std::log(static_cast<double>(n));
}

std::vector<double> GridEstimator::spreads_at(Vec2 p) const {
  return likelihood_.sigma_std > 0.0 ? model_.spreads_at(p) : std::vector<double>{};
}

void GridEstimator::accumulate(Sums& sums, const std::vector<double>& r,
                               const std::vector<double>& spread, double value,
                               double weight) const {
  const double s_ref = 0.5 * (scale_lo_ + scale_hi_);
  for (std::size_t k = 0; k < r.size(); ++k) {
    const double var = likelihood_.variance(s_ref * r[k], spread.empty() ? 0.0 : s_ref * spread[k]);
    const double w = weight / var;
    sums.a[k] += w * r[k] * r[k];
    sums.b[k] += w * r[k] * value;
    sums.c[k] += w * value * value;
    sums.h[k] += weight * std::log(var);
  }
}

void GridEstimator::add(Vec2 p, double value) {
  accumulate(sums_, model_.readings_at(p), spreads_at(p), value);
  ++samples_;
}

void GridEstimator::add_partial(Vec2 p, double value, double weight) {
  check_weight(weight);
  accumulate(sums_, model_.readings_at(p), spreads_at(p), value, weight);
}

std::vector<double> GridEstimator::log_weights(const Sums& sums) const {
  const std::vector<std::uint8_t>& ok = model_.allowed();
  const std::vector<double>&a = sums.a, &b = sums.b, &c = sums.c, &h = sums.h;
  std::vector<double> l(a.size(), -kInf);
  double top = -kInf;
  for (std::size_t k = 0; k < a.size(); ++k) {
    if (!ok[k]) continue;
    if (scale_hi_ == scale_lo_) {
      const double s = scale_lo_;
      l[k] = -0.5 * (c[k] - 2.0 * s * b[k] + s * s * a[k]);
    } else {
      l[k] = log_marginal_scale(a[k], b[k], c[k], 1.0, scale_lo_, scale_hi_);
    }
    l[k] -= 0.5 * h[k];
    top = std::max(top, l[k]);
  }
  double sum = 0.0;
  for (double v : l)
    if (v > -kInf) sum += std::exp(v - top);
  const double norm = top + std::log(sum);
  for (double& v : l)
    if (v > -kInf) v -= norm;
  return l;
}

Posterior GridEstimator::posterior() {
  const std::vector<double> l = log_weights(sums_);
  const GridShape& g = model_.candidates();
  Posterior post;
  post.marginal = Grid<double>(g, 0.0);
  double ex = 0.0, ey = 0.0, es = 0.0, best = -kInf, seen = 0.0;
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      const std::size_t k = g.index(i, j);
      if (l[k] == -kInf) continue;
      const double w = std::exp(l[k]);
      post.marginal.values[k] = w;
      const Vec2 c = g.centre(i, j);
      ex += w * c.x;
      ey += w * c.y;
      es += w * (scale_hi_ == scale_lo_
                     ? scale_lo_
                     : mean_scale(sums_.a[k], sums_.b[k], 1.0, scale_lo_, scale_hi_));
      if (l[k] > best) best = l[k], post.map = c;
      if (sums_.a[k] >= Posterior::kSeenSigmas * Posterior::kSeenSigmas) seen += w;
    }
  post.expected = {ex, ey, es};
  post.entropy = entropy_on_bins(post.marginal, bins_);
  post.max_entropy = max_entropy_;
  post.seen_mass = seen;
  return post;
}

double GridEstimator::predicted_from(const std::vector<double>& r, const Posterior& current) const {
  const int at = model_.nearest_allowed(current.expected_source());
  return at < 0 ? 0.0 : current.expected.at(2) * r[at];
}

double GridEstimator::predicted_reading(Vec2 p, const Posterior& current) const {
  return predicted_from(model_.readings_at(p), current);
}

double GridEstimator::information_gain(Vec2 p, const Posterior& current) const {
  const std::vector<double> r = model_.readings_at(p);
  const double predicted = predicted_from(r, current);
  Sums after = sums_;
  accumulate(after, r, spreads_at(p), predicted);
  const std::vector<double> lq = log_weights(after);
  double kl = 0.0;
  for (std::size_t k = 0; k < lq.size(); ++k) {
    const double pk = current.marginal.values[k];
    if (pk <= 0.0 || lq[k] == -kInf) continue;
    kl += pk * (std::log(pk) - lq[k]);
  }
  return std::max(0.0, kl);
}

std::vector<std::pair<std::size_t, double>> GridEstimator::gain_support(
    const std::vector<double>& w, int max_cells) {
  std::vector<std::pair<std::size_t, double>> support;
  for (std::size_t k = 0; k < w.size(); ++k)
    if (w[k] > 0.0) support.emplace_back(k, w[k]);
  if (support.size() <= static_cast<std::size_t>(max_cells)) return support;
  // Systematic resampling: the cells at the quantiles (j + 1/2) / N of the cumulative mass, each
  // weighted by the quantiles it takes.
  std::vector<std::pair<std::size_t, double>> picked;
  double cum = 0.0;
  int j = 0;
  for (const auto& [k, weight] : support) {
    cum += weight;
    int hits = 0;
    while (j < max_cells && (j + 0.5) / max_cells <= cum)
      ++j, ++hits;
    if (hits > 0) picked.emplace_back(k, static_cast<double>(hits) / max_cells);
  }
  return picked;
}

double GridEstimator::expected_information_gain(Vec2 p, const Posterior& current) const {
  return expected_information_gains({p}, current, 0).front();
}

std::vector<double> GridEstimator::expected_information_gains(const std::vector<Vec2>& points,
                                                              const Posterior& current,
                                                              int max_cells) const {
  std::vector<double> gains(points.size(), 0.0);
  const std::vector<double>& w = current.marginal.values;
  const double s = current.expected.at(2);
  // The hypotheses: the cells at the quantiles (j + 1/2) / J of the cumulative mass; a cell hit
  // by several quantiles counts that many times.
  std::vector<std::pair<std::size_t, int>> picks;
  double cum = 0.0;
  int j = 0;
  for (std::size_t k = 0; k < w.size() && j < hypotheses; ++k) {
    cum += w[k];
    int hits = 0;
    while (j < hypotheses && (j + 0.5) / hypotheses <= cum)
      ++j, ++hits;
    if (hits > 0) picks.emplace_back(k, hits);
  }
  if (picks.empty() || points.empty()) return gains;
  const auto support = gain_support(w, max_cells > 0 ? max_cells : static_cast<int>(w.size()));
  // For a reading z, Q_k = P_k L_k(z) / Z and KL(Q || P) = sum_k Q_k log L_k - log Z. A cell's
  // prediction and variance do not depend on z: they are computed once per point.
  struct Cell {
    double weight, mean, inv_var, log_var;
  };
  std::vector<Cell> cells;
  std::vector<double> ll(support.size());
  const double var0 = likelihood_.variance(0.0, 0.0);
  const Cell silent{0.0, 0.0, 1.0 / var0, likelihood_.variance_varies() ? std::log(var0) : 0.0};
  for (std::size_t i = 0; i < points.size(); ++i) {
    const std::vector<double> r = model_.readings_at(points[i]);
    const std::vector<double> spread = spreads_at(points[i]);
    cells.clear();
    // Approximate (max_cells > 0): the cells whose plume does not reach the point (a prediction
    // and spread below 1e-4 sigma) are one cell, the silent one, of their summed weight.
    Cell quiet = silent;
    const double faint = 1e-4 * std::sqrt(var0);
    for (const auto& [k, weight] : support) {
      const double mean = s * r[k], sd = spread.empty() ? 0.0 : s * spread[k];
      if (max_cells > 0 && std::abs(mean) < faint && sd < faint) {
        quiet.weight += weight;
        continue;
      }
      const double var = likelihood_.variance(mean, sd);
      cells.push_back(
          {weight, mean, 1.0 / var, likelihood_.variance_varies() ? std::log(var) : 0.0});
    }
    if (quiet.weight > 0.0) cells.push_back(quiet);
    double gain = 0.0;
    int counted = 0;
    for (const auto& [pick, hits] : picks) {
      const double z = s * r[pick];
      double top = -kInf;
      for (std::size_t k = 0; k < cells.size(); ++k) {
        const double d = z - cells[k].mean;
        ll[k] = -0.5 * (d * d * cells[k].inv_var + cells[k].log_var);
        top = std::max(top, ll[k]);
      }
      double z_sum = 0.0, q_ll = 0.0;
      for (std::size_t k = 0; k < cells.size(); ++k) {
        const double q = cells[k].weight * std::exp(ll[k] - top);
        z_sum += q;
        q_ll += q * (ll[k] - top);
      }
      gain += hits * std::max(0.0, q_ll / z_sum - std::log(z_sum));
      counted += hits;
    }
    gains[i] = gain / counted;
  }
  return gains;
}

}  // namespace plumekit::ste
