#include "methods/local_framework.hpp"

#include "methods/method_options.hpp"
#include "methods/registry.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "core/option_check.hpp"
#include "core/seed.hpp"
#include "methods/option_tables.hpp"

namespace plumekit::methods {

const OptionTable<LocalFrameworkOptions>& local_option_table() {
  using O = LocalFrameworkOptions;
  static const OptionTable<O> table{
      "STE in the local framework (methods::LocalFrameworkOptions)",
      {{"local.budget", "--budget", &O::budget, positive(1000.0, "samples"),
        "ste-local: samples per local map when nothing is learnt, B_0 of seed 004 Eq. 12.1",
        "the thesis's B_0 is {default}"},
       {"local.map_size", "--local-map", &O::map_size, positive(100.0, "m"),
        "ste-local: the local map's side, m", "the thesis's local map is {default} m"},
       {"local.max_samples", "", &O::max_samples, count_range(1, 100'000),
        "Samples in all before the run declares (the run's step budget replaces it)"},
       {"local.sigma_m", "", &O::sigma_m, positive(1e9, "concentration units"),
        "The likelihood's model error, concentration units", "the thesis's is {default}"},
       {"local.entropy_fraction", "", &O::entropy_fraction, non_negative(1.0, ""),
        "Stop when the local posterior's entropy falls below this fraction of its maximum",
        "the thesis's is {default}"}}};
  return table;
}

void LocalFrameworkOptions::validate() const {
  plumekit::validate(local_option_table(), *this);
  mh.validate();
  navigation.validate();
}

double next_budget(double budget, double current, double previous) {
  const double ratio = current / previous;
  return ratio >= 1.0 ? budget - 1.0 : budget - ratio;
}

namespace {

// A square arena of `size` with the wind blowing in at `speed` through its left side: the local
// map in its own frame, x downwind.
Map window_map(double size, double speed) {
  Map m = default_arena(size, size);
  m.name = "local map";
  m.openings.front().speed = speed;
  m.openings.front().profile = Profile::Uniform;
  return m;
}

}  // namespace

// One local map: the frame (centre and wind, odometry coordinates), the plume model bounded to
// it, and the estimation and navigation on it.
struct LocalFrameworkSte::Window {
  Window(Vec2 centre_, Vec2 downwind_, double speed, const LocalFrameworkOptions& o,
         std::uint64_t seed)
      : centre(centre_),
        downwind(downwind_),
        half(0.5 * o.map_size),
        map(window_map(o.map_size, speed)),
        model(map),
        bins(ste::make_bins(map, ste::BinOptions{})),
        space(map, 0.05, 16),
        navigator(space, bins, lattice(o.navigation)),
        estimator(model, map, likelihood(o), bins, o.mh, seed) {}

  static ste::NavigationOptions lattice(ste::NavigationOptions n) {
    n.candidates = ste::NavigationOptions::Candidates::Lattice;
    n.reward = ste::NavigationOptions::Reward::Kl;  // MH's
    return n;
  }
  static ste::LikelihoodOptions likelihood(const LocalFrameworkOptions& o) {
    ste::LikelihoodOptions l;
    l.sigma_m = o.sigma_m;
    return l;
  }
  // Odometry <-> the map's frame ([0, size]^2, x downwind).
  Vec2 to_local(Vec2 p) const {
    const Vec2 d = p - centre;
    return {dot(d, downwind) + half, cross(downwind, d) + half};
  }
  Vec2 to_odometry(Vec2 q) const {
    const Vec2 left{-downwind.y, downwind.x};
    return centre + (q.x - half) * downwind + (q.y - half) * left;
  }
  bool contains(Vec2 p) const {
    const Vec2 q = to_local(p);
    return q.x >= 0.0 && q.x <= map.width && q.y >= 0.0 && q.y <= map.height;
  }

  Vec2 centre, downwind;
  double half;
  Map map;
  ste::GaussianPlume model;
  GridShape bins;
  planner::FreeSpace space;
  ste::Navigator navigator;
  ste::MhEstimator estimator;
  ste::Posterior posterior;
};

LocalFrameworkSte::LocalFrameworkSte(const LocalFrameworkOptions& options, std::uint64_t seed)
    : options_(options), rng_(seed), seed_(seed) {
  options_.validate();
}

LocalFrameworkSte::~LocalFrameworkSte() = default;

int LocalFrameworkSte::map_samples() const {
  return window_ ? window_->estimator.samples() : 0;
}

void LocalFrameworkSte::open_map(Vec2 centre, Vec2 wind) {
  const double speed = std::max(norm(wind), 0.05);  // a calm still has a direction to align to
  if (norm(wind) > 1e-9) wind_ = (1.0 / norm(wind)) * wind;
  window_ = std::make_unique<Window>(centre, wind_, speed, options_,
                                     splitmix64(seed_ + static_cast<std::uint64_t>(maps_)));
  budget_ = options_.budget;
  previous_entropy_ = -1.0;
  sensed_ = 0.0;
  ++maps_;
}

void LocalFrameworkSte::observe(const methods::Observation& o) {
  methods::check_observation(o, "ste-local");
  odometry_ = o.position;
  // The first stop, and the first in a new map: open it here, aligned with the wind read here.
  if (!window_ || moving_map_) open_map(o.position, o.wind);
  moving_map_ = false;
  // An obstacle stopped the robot: its goal gets a measurement of 0 (Algorithm 1).
  Vec2 at = o.position;
  double value = o.gas;
  if (o.blocked) {
    at = last_goal_;
    value = 0.0;
  }
  ++samples_;
  if (window_->contains(at)) {
    window_->estimator.add(window_->to_local(at), value);
    sensed_ += value;
  }
  if (window_->estimator.samples() == 0) return;  // an obstacle's 0 outside the map
  window_->posterior = window_->estimator.posterior();
  const ste::Posterior& p = window_->posterior;
  estimate_ = window_->to_odometry(p.expected_source());
  budget_ =
      previous_entropy_ > 0.0 ? next_budget(budget_, p.entropy, previous_entropy_) : budget_ - 1.0;
  previous_entropy_ = p.entropy;
  // A source beyond the map's upwind side looks like one on it: the posterior piles up in the
  // upwind column of bins. Certain there, the robot moves the map on instead of declaring.
  const bool on_upwind_edge = p.expected_source().x < window_->bins.dx();
  if (p.entropy < options_.entropy_fraction * p.max_entropy && !on_upwind_edge)
    stopped_by_ = "entropy";
  else if (samples_ >= options_.max_samples)
    stopped_by_ = "max_samples";
}

methods::Move LocalFrameworkSte::next(Vec2 robot) {
  Vec2 goal;
  const Window& w = *window_;
  if (budget_ <= 0.0 || w.estimator.samples() == 0) {
    // Move the map: crosswind when nothing was sensed in it, else onto its MAP.
    if (sensed_ <= 0.0 || w.estimator.samples() == 0) {
      const Vec2 left{-w.downwind.y, w.downwind.x};
      const double side = std::uniform_int_distribution<int>(0, 1)(rng_) == 0 ? -1.0 : 1.0;
      goal = odometry_ + side * options_.map_size * left;
    } else {
      goal = w.to_odometry(w.posterior.map);
    }
    moving_map_ = true;
  } else {
    const ste::Decision d = w.navigator.decide(w.to_local(odometry_), w.estimator, w.posterior);
    goal = w.to_odometry(d.goal);
  }
  last_goal_ = goal;
  methods::Move m;
  m.goal = robot + (goal - odometry_);  // the same move from where the robot truly is
  m.straight = true;
  return m;
}

MethodSpec ste_local_spec() {
  return {"ste-local",
          "STE in the local framework: no map, odometry, a moving local map",
          "seed 004 ch. 12",
          MethodTraits{false, RunEnd::OwnStopRule},
          [](const MethodOptions& o, const SearchArea&, std::uint64_t seed) {
            LocalFrameworkOptions local = o.local;
            local.max_samples = o.tracking.max_steps;
            return std::make_unique<LocalFrameworkSte>(local, seed);
          },
          [](const MethodOptions& m, nlohmann::ordered_json& j) {
            j["map_size_m"] = m.local.map_size;
            j["budget"] = m.local.budget;
            j["sigma_m"] = m.local.sigma_m;  // its sample guard is max_steps
          }};
}

}  // namespace plumekit::methods
