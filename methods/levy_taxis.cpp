#include "methods/levy_taxis.hpp"

#include "methods/method_options.hpp"
#include "methods/registry.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/option_check.hpp"
#include "core/random.hpp"
#include "methods/option_tables.hpp"

namespace plumekit::methods {

const OptionTable<LevyTaxisOptions>& levy_option_table() {
  using O = LevyTaxisOptions;
  const double inf = std::numeric_limits<double>::infinity();
  // The move and turn ranges depend on each other: validate() checks them in order.
  static const OptionTable<O> table{
      "Lévy taxis (methods::LevyTaxisOptions)",
      {{"levy.min_move", "", &O::min_move, positive(100.0, "m"), "Shortest move L_min, m",
        "the thesis's {default} m"},
       {"levy.max_move",
        "",
        &O::max_move,
        {},
        "Longest move (longer draws are cut to it), m",
        "",
        "more than levy.min_move, at most 1000 m"},
       {"levy.mu_min", "", &O::mu_min, real_range(1.0, 3.0, "", true), "Smallest exponent mu",
        "1 < mu <= 3; the thesis's {default}"},
       {"levy.mu_max",
        "",
        &O::mu_max,
        {},
        "Largest exponent mu",
        "",
        "at least levy.mu_min, at most 3"},
       {"levy.gamma_min", "", &O::gamma_min, real_range(0.0, 1.0, ""),
        "Least concentration gamma of the turns", "the thesis's {default}"},
       {"levy.gamma_max",
        "",
        &O::gamma_max,
        {},
        "Most concentration gamma of the turns",
        "",
        "at least levy.gamma_min, at most 1"},
       {"levy.gradient_threshold", "--levy-threshold", &O::gradient_threshold,
        positive(inf, "concentration units"),
        "Lévy taxis: a change of the reading between stops from which the walk is all "
        "exploitation (longest, straightest moves), concentration units (theta of seed 004 "
        "Eq. 16.3, which it does not give; docs/methods.md)"},
       {"levy.max_steps", "", &O::max_steps, count_range(1, 10000000),
        "Stops before the walk gives up (the run's step budget replaces it)"}}};
  return table;
}

void LevyTaxisOptions::validate() const {
  // In order: each upper bound is checked against its lower one once that one is known good.
  const OptionTable<LevyTaxisOptions>& table = levy_option_table();
  validate_entry(table.entry("levy.min_move"), *this);
  check_range("levy.max_move", max_move, min_move, 1000.0, "m",
              "it must exceed levy.min_move; the thesis's 2 m", true);
  validate_entry(table.entry("levy.mu_min"), *this);
  check_range("levy.mu_max", mu_max, mu_min, 3.0, "",
              "at least levy.mu_min and at most 3; the thesis's 2.9");
  validate_entry(table.entry("levy.gamma_min"), *this);
  check_range("levy.gamma_max", gamma_max, gamma_min, 1.0, "",
              "at least levy.gamma_min and at most 1; the thesis's 1");
  validate_entry(table.entry("levy.gradient_threshold"), *this);
  validate_entry(table.entry("levy.max_steps"), *this);
}

double levy_move_length(double u, double mu, double min_move, double max_move) {
  // u = 0 would be an infinite move: the cut takes it.
  if (u <= 0.0) return max_move;
  return std::min(max_move, min_move * std::pow(u, 1.0 / (1.0 - mu)));
}

double wrapped_cauchy_turn(double u, double gamma) {
  return 2.0 * std::atan((1.0 - gamma) / (1.0 + gamma) * std::tan(kPi * (u - 0.5)));
}

LevyShape adapt_levy_shape(double gradient, const LevyTaxisOptions& o) {
  const double f = std::min(1.0, std::abs(gradient) / o.gradient_threshold);
  return {o.mu_max - f * (o.mu_max - o.mu_min), o.gamma_min + f * (o.gamma_max - o.gamma_min)};
}

AdaptiveLevyTaxis::AdaptiveLevyTaxis(const LevyTaxisOptions& options, std::uint64_t seed)
    : options_(options), rng_(seed) {
  options_.validate();
}

void AdaptiveLevyTaxis::observe(const Observation& o) {
  check_observation(o, name());
  ++stops_;
  // A calm stop keeps the last upwind direction, as the trackers do.
  if (norm(o.wind) > 1e-9) upwind_ = std::atan2(-o.wind.y, -o.wind.x);
  // Eq. 16.3: the change since the last stop (not divided by the distance); none at the first.
  const double gradient = previous_gas_ ? o.gas - *previous_gas_ : 0.0;
  shape_ = adapt_levy_shape(gradient, options_);
  // Rising: the mean of the heading and upwind (a low-pass on the heading); else upwind alone.
  bias_ = upwind_;
  if (gradient > 0.0 && norm(step_) > 0.0) {
    const double heading = std::atan2(step_.y, step_.x);
    const double sx = std::cos(heading) + std::cos(upwind_),
                 sy = std::sin(heading) + std::sin(upwind_);
    if (std::hypot(sx, sy) > 1e-9) bias_ = std::atan2(sy, sx);
  }
  const double length =
      levy_move_length(1.0 - uniform01(rng_), shape_.mu, options_.min_move, options_.max_move);
  const double turn = bias_ + wrapped_cauchy_turn(uniform01(rng_), shape_.gamma);
  step_ = {length * std::cos(turn), length * std::sin(turn)};
  previous_gas_ = o.gas;
}

Move AdaptiveLevyTaxis::next(Vec2 robot) {
  Move m;
  m.goal = robot + step_;
  return m;
}

std::string AdaptiveLevyTaxis::stopped_by() const {
  return stops_ >= options_.max_steps ? "max_samples" : "";
}

MethodSpec levy_taxis_spec() {
  return {"levy-taxis",
          "adaptive Levy taxis: a random walk whose steps adapt to the gas",
          "seed 004 ch. 16",
          MethodTraits{false, RunEnd::SourceDisc},
          [](const MethodOptions& o, const SearchArea&, std::uint64_t seed) {
            LevyTaxisOptions levy = o.levy;
            levy.max_steps = o.tracking.max_steps;
            return std::make_unique<AdaptiveLevyTaxis>(levy, seed);
          },
          [](const MethodOptions& m, nlohmann::ordered_json& j) {
            const LevyTaxisOptions& l = m.levy;
            j["min_move_m"] = l.min_move;
            j["max_move_m"] = l.max_move;
            j["mu"] = {l.mu_min, l.mu_max};
            j["gamma"] = {l.gamma_min, l.gamma_max};
            j["gradient_threshold"] = l.gradient_threshold;
          }};
}

}  // namespace plumekit::methods
