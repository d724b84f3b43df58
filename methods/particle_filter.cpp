#include "methods/particle_filter.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>
#include <string>
#include <utility>

#include "core/error.hpp"
#include "core/option_check.hpp"
#include "methods/option_tables.hpp"
#include "methods/wind_statistics.hpp"

namespace plumekit::methods {

namespace {

// Bounds on rejection sampling: a free point of a cluttered map, and an injected point in a
// region that may be a sliver (F ∩ S_t when the robot stands at the upwind wall).
constexpr int kFreeTries = 10000;
constexpr int kInjectTries = 1000;
constexpr int kJitterTries = 16;
// Boundary points count as inside C_t despite round-off.
constexpr double kOnBoundary = 1e-12;

// Sutherland-Hodgman against the half-plane value(p) >= 0 of a linear `value`. The subject may be
// non-convex (the PPE for S0 > 0.5); the clip region is convex, so the result is right, at worst
// with a zero-width spur along the clip line.
Polygon clip(const Polygon& poly, const std::function<double(Vec2)>& value) {
  Polygon out;
  if (poly.empty()) return out;
  Vec2 a = poly.back();
  double va = value(a);
  for (Vec2 b : poly) {
    const double vb = value(b);
    if ((va >= 0.0) != (vb >= 0.0)) out.push_back(a + (va / (va - vb)) * (b - a));
    if (vb >= 0.0) out.push_back(b);
    a = b;
    va = vb;
  }
  return out;
}

Polygon without_repeats(const Polygon& poly) {
  Polygon out;
  for (Vec2 p : poly) {
    if (out.empty() || norm(p - out.back()) > 1e-12) out.push_back(p);
  }
  while (out.size() > 1 && norm(out.front() - out.back()) <= 1e-12)
    out.pop_back();
  return out;
}

void check_finite(double v, const char* what) {
  if (!std::isfinite(v))
    throw InputError(std::string("pf: the observation's ") + what + " is not finite");
}

}  // namespace

const OptionTable<ParticleFilterOptions>& particle_filter_option_table() {
  using O = ParticleFilterOptions;
  static const OptionTable<O> table{
      "Particle filter (methods::ParticleFilterOptions)",
      {{"pf.particles", "--particles", &O::particles, count_range(1, 10000000),
        "Particle filter: particles"},
       {"pf.alpha", "", &O::alpha, positive(1.0, ""),
        "Penalty alpha of a particle outside the patch path envelope on a detection (1: none)",
        "the seeds' best are 0.4 (sweep), 0.2 (gradient)"},
       {"pf.beta", "", &O::beta, positive(1.0, ""), "Penalty beta on a non-detection (1: none)",
        "the seeds' best are 0.9 (sweep), 0.8 (gradient)"},
       {"pf.resample_fraction", "", &O::resample_fraction, non_negative(1.0, ""),
        "gamma: resample when N_eff < gamma N"},
       {"pf.injection", "", &O::injection, non_negative(1.0, ""),
        "delta: share of resampled particles drawn uniformly"},
       {"pf.jitter_variance", "", &O::jitter_variance, non_negative(100.0, "m^2"),
        "Jitter variance per axis of particles drawn by weight, m^2"},
       {"pf.mne_radius", "", &O::mne_radius, positive(1000.0, "m"),
        "epsilon: radius of the mean neighbourhood estimate, m"},
       {"pf.detection_limit", "", &O::detection_limit, non_negative(1e300, ""),
        "th_c, concentration units: readings below count 0 (run by the trackers' "
        "--detection-threshold)"},
       {"pf.ema_lambda", "", &O::ema_lambda, non_negative(1.0, ""),
        "lambda of the adaptive threshold (seed 001 Eq. 4)"},
       {"pf.min_opening_deg", "", &O::min_opening_deg, positive(180.0, "deg"),
        "Floor of the envelope's opening theta_C, degrees (a steady wind gives 0)"}}};
  return table;
}

void ParticleFilterOptions::validate() const {
  plumekit::validate(particle_filter_option_table(), *this);
}

AdaptiveThreshold::AdaptiveThreshold(double detection_limit, double lambda)
    : limit_(detection_limit), lambda_(lambda) {}

bool AdaptiveThreshold::update(double gas) {
  const double c = gas < limit_ ? 0.0 : gas;
  const bool z = readings_ > 0 && c > average_;
  average_ = readings_ > 0 ? lambda_ * average_ + (1.0 - lambda_) * c : c;
  ++readings_;
  return z;
}

bool PatchPathEnvelope::contains(Vec2 q) const {
  const bool in_triangle = orient(m0, r1, q) >= -kOnBoundary && orient(r1, l1, q) >= -kOnBoundary &&
                           orient(l1, m0, q) >= -kOnBoundary;
  if (in_triangle) return true;
  // Beyond the triangle: upwind of the line l1-r1 and between the two rays.
  return dot(q - position, up) >= -kOnBoundary && orient(r1, r1 + right_ray, q) >= -kOnBoundary &&
         orient(l1, l1 + left_ray, q) <= kOnBoundary;
}

PatchPathEnvelope make_envelope(Vec2 position, Vec2 wind, double s0, double width, double height,
                                double min_opening_deg) {
  PatchPathEnvelope e;
  e.position = position;
  e.up = upwind(wind);
  const Vec2 left = rotate(e.up, kPi / 2.0);  // the seeds' theta_u - 90 deg (azimuths turn cw)
  e.m0 = position - 0.5 * e.up;
  e.l1 = position + 0.5 * left;
  e.r1 = position - 0.5 * left;
  const double half = radians(90.0) * s0;  // Eq. 5: theta_u -+ 90 deg S0, outward
  e.left_ray = rotate(e.up, half);
  e.right_ray = rotate(e.up, -half);
  e.opening_deg = std::max(180.0 * s0, min_opening_deg);

  // The wedge as a polygon whose far vertices lie well outside the rectangle: at a distance L
  // along both rays and straight upwind, so that no chord between them cuts the rectangle even
  // for an opening of 180 deg (each chord stays >= (L - 0.5) cos 45 deg from the robot).
  double reach = 0.0;
  for (Vec2 c : {Vec2{0.0, 0.0}, Vec2{width, 0.0}, Vec2{0.0, height}, Vec2{width, height}})
    reach = std::max(reach, norm(c - position));
  const double L = 2.0 * (reach + 1.0);
  Polygon wedge{e.m0, e.r1, e.r1 + L * e.right_ray, position + L * e.up, e.l1 + L * e.left_ray,
                e.l1};
  wedge = clip(wedge, [](Vec2 p) { return p.x; });
  wedge = clip(wedge, [width](Vec2 p) { return width - p.x; });
  wedge = clip(wedge, [](Vec2 p) { return p.y; });
  wedge = clip(wedge, [height](Vec2 p) { return height - p.y; });
  e.polygon = without_repeats(wedge);
  return e;
}

ParticleClass classify(const PatchPathEnvelope& envelope, Vec2 q) {
  if (envelope.contains(q)) return ParticleClass::Inside;
  return envelope.upwind_of_s(q) ? ParticleClass::Upwind : ParticleClass::Downwind;
}

double weight_factor(ParticleClass c, bool detection, double alpha, double beta,
                     double opening_deg) {
  const double r = opening_deg / 180.0;
  switch (c) {
    case ParticleClass::Inside:
      return detection ? 1.0 : beta * beta * r;
    case ParticleClass::Upwind:
      return detection ? alpha * r : beta;
    case ParticleClass::Downwind:
      return detection ? alpha * alpha * r : 1.0;
  }
  return 1.0;
}

bool normalize_weights(std::vector<double>& weights) {
  const double sum = std::accumulate(weights.begin(), weights.end(), 0.0);
  if (!(sum > 0.0) || !std::isfinite(sum)) {
    std::fill(weights.begin(), weights.end(), 1.0 / static_cast<double>(weights.size()));
    return false;
  }
  for (double& w : weights)
    w /= sum;
  return true;
}

double effective_sample_size(const std::vector<double>& weights) {
  double sq = 0.0;
  for (double w : weights)
    sq += w * w;
  return sq > 0.0 ? 1.0 / sq : 0.0;
}

std::vector<int> carpenter_resample(const std::vector<double>& weights, int count,
                                    std::mt19937_64& rng) {
  std::vector<int> idx;
  if (count <= 0 || weights.empty()) return idx;
  const int n = static_cast<int>(weights.size());
  std::vector<double> q(weights.size());
  std::partial_sum(weights.begin(), weights.end(), q.begin());
  // The last particle with weight, where the merge ends when round-off leaves Q_N below T_i.
  int last = n - 1;
  while (last > 0 && !(weights[last] > 0.0))
    --last;
  // Sorted uniforms in linear time: the normalised cumulative sums of count + 1 exponentials
  // (1 - u lies in (0, 1], so the logarithm is finite).
  std::vector<double> t(static_cast<std::size_t>(count) + 1);
  double total = 0.0;
  for (double& ti : t) {
    total += -std::log(1.0 - uniform01(rng));
    ti = total;
  }
  idx.reserve(count);
  const double scale = q.back() / total;  // weights need not sum to exactly 1
  int j = 0;
  for (int i = 0; i < count; ++i) {
    const double ti = t[i] * scale;
    while (j < last && !(ti < q[j]))
      ++j;
    idx.push_back(j);
  }
  return idx;
}

std::vector<int> neighbour_counts(const std::vector<Vec2>& particles, double radius) {
  const int n = static_cast<int>(particles.size());
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    return particles[a].x < particles[b].x || (particles[a].x == particles[b].x && a < b);
  });
  // Sweep in x: only the particles within `radius` in x of one can be its neighbours.
  std::vector<int> count(n, 0);
  const double r2 = radius * radius;
  for (int a = 0; a < n; ++a) {
    const Vec2 p = particles[order[a]];
    for (int b = a + 1; b < n; ++b) {
      const Vec2 d = particles[order[b]] - p;
      if (d.x > radius) break;
      if (d.x * d.x + d.y * d.y <= r2) {
        ++count[order[a]];
        ++count[order[b]];
      }
    }
  }
  return count;
}

NeighbourCount most_neighbours(const std::vector<int>& counts, const std::vector<double>& weights) {
  NeighbourCount best;
  if (counts.empty()) return best;
  best.index = 0;
  for (int i = 1; i < static_cast<int>(counts.size()); ++i) {
    if (counts[i] > counts[best.index] ||
        (counts[i] == counts[best.index] && weights[i] > weights[best.index]))
      best.index = i;
  }
  best.neighbours = counts[best.index];
  return best;
}

NeighbourCount maximum_neighbours(const std::vector<Vec2>& particles,
                                  const std::vector<double>& weights, double radius) {
  return most_neighbours(neighbour_counts(particles, radius), weights);
}

ParticleFilter::ParticleFilter(const SearchArea& area, const ParticleFilterOptions& options,
                               std::uint64_t seed)
    : area_(area),
      options_(options),
      rng_(seed),
      threshold_(options.detection_limit, options.ema_lambda) {
  options_.validate();
  const int n = options_.particles;
  particles_.reserve(n);
  for (int i = 0; i < n; ++i) {
    const std::optional<Vec2> p = draw_free();
    if (!p) throw InputError("pf: found no free point in the search area to place a particle on");
    particles_.push_back(*p);
  }
  weights_.assign(n, 1.0 / n);
  counts_ = neighbour_counts(particles_, options_.mne_radius);
  mne_ = most_neighbours(counts_, weights_);
  step_.effective_size = n;
}

void ParticleFilter::set_particles(std::vector<Vec2> particles, std::vector<double> weights) {
  if (particles.empty() || particles.size() != weights.size())
    throw InputError("pf: set_particles needs as many weights as particles, at least one");
  for (std::size_t i = 0; i < particles.size(); ++i) {
    if (!is_finite(particles[i]) || !std::isfinite(weights[i]) || weights[i] < 0.0)
      throw InputError("pf: set_particles needs finite particles and finite weights >= 0");
  }
  particles_ = std::move(particles);
  weights_ = std::move(weights);
  counts_ = neighbour_counts(particles_, options_.mne_radius);
  mne_ = most_neighbours(counts_, weights_);
}

const FilterStep& ParticleFilter::update(const Observation& o) {
  check_finite(o.position.x, "position");
  check_finite(o.position.y, "position");
  check_finite(o.gas, "gas reading");
  check_finite(o.wind.x, "wind");
  check_finite(o.wind.y, "wind");
  check_finite(o.wind_variance, "wind variance");
  const bool detection = threshold_.update(o.gas);
  if (norm(o.wind) < 1e-9) {
    // A calm carries no gas patch along a direction: no PPE, nothing to weigh by.
    step_ = FilterStep{};
    step_.detection = detection;
    step_.effective_size = effective_sample_size(weights_);
    ++iterations_;
    return step_;
  }
  const double s0 = std::clamp(o.wind_variance, 0.0, 1.0);
  return update(make_envelope(o.position, o.wind, s0, area_.width(), area_.height(),
                              options_.min_opening_deg),
                detection);
}

const FilterStep& ParticleFilter::update(const PatchPathEnvelope& envelope, bool detection) {
  for (std::size_t i = 0; i < particles_.size(); ++i) {
    weights_[i] *= weight_factor(classify(envelope, particles_[i]), detection, options_.alpha,
                                 options_.beta, envelope.opening_deg);
  }
  step_ = FilterStep{};
  step_.detection = detection;
  step_.envelope = envelope;
  step_.weights_reset = !normalize_weights(weights_);
  step_.effective_size = effective_sample_size(weights_);
  step_.resampled =
      step_.effective_size < options_.resample_fraction * static_cast<double>(particles_.size());
  if (step_.resampled) {
    resample(envelope, detection);
    counts_ = neighbour_counts(particles_, options_.mne_radius);
  }
  mne_ = most_neighbours(counts_, weights_);
  ++iterations_;
  return step_;
}

// Seed 001 Algorithm 1 lines 8-21: each new particle is, with probability delta, a uniform draw
// from F ∩ S_t (detection) or F \ C_t (none), else a draw by weight with Gaussian jitter.
// An injection that finds no point in its region is drawn by weight instead.
void ParticleFilter::resample(const PatchPathEnvelope& envelope, bool detection) {
  const int n = static_cast<int>(particles_.size());
  std::vector<std::optional<Vec2>> injected(n);
  int drawn = n;
  for (int i = 0; i < n; ++i) {
    if (uniform01(rng_) < options_.injection) {
      injected[i] = draw_injected(envelope, detection);
      if (injected[i]) --drawn;
    }
  }
  const std::vector<int> idx = carpenter_resample(weights_, drawn, rng_);
  std::vector<Vec2> next;
  next.reserve(n);
  int k = 0;
  for (int i = 0; i < n; ++i)
    next.push_back(injected[i] ? *injected[i] : jittered(particles_[idx[k++]]));
  particles_ = std::move(next);
  weights_.assign(n, 1.0 / n);
}

std::optional<Vec2> ParticleFilter::draw_injected(const PatchPathEnvelope& envelope,
                                                  bool detection) {
  for (int i = 0; i < kInjectTries; ++i) {
    const Vec2 q{uniform(rng_, 0.0, area_.width()), uniform(rng_, 0.0, area_.height())};
    if (!area_.is_free(q)) continue;
    if (detection ? envelope.upwind_of_s(q) : !envelope.contains(q)) return q;
  }
  return std::nullopt;
}

std::optional<Vec2> ParticleFilter::draw_free() {
  for (int i = 0; i < kFreeTries; ++i) {
    const Vec2 q{uniform(rng_, 0.0, area_.width()), uniform(rng_, 0.0, area_.height())};
    if (area_.is_free(q)) return q;
  }
  return std::nullopt;
}

// Jitter clamped to the rectangle; redrawn when it lands in an obstacle, and the position itself
// when every redraw does (a particle next to an obstacle stays put rather than jumping over it).
Vec2 ParticleFilter::jittered(Vec2 p) {
  const double sd = std::sqrt(options_.jitter_variance);
  if (sd == 0.0) return p;
  for (int i = 0; i < kJitterTries; ++i) {
    const double dx = normal(normal_, rng_, 0.0, sd);
    const double dy = normal(normal_, rng_, 0.0, sd);
    const Vec2 q{std::clamp(p.x + dx, 0.0, area_.width()),
                 std::clamp(p.y + dy, 0.0, area_.height())};
    if (area_.is_free(q)) return q;
  }
  return p;
}

}  // namespace plumekit::methods
