#include "methods/apf_planner.hpp"

#include "methods/method_options.hpp"
#include "methods/registry.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "core/error.hpp"
#include "core/option_check.hpp"
#include "methods/gdm_estimates.hpp"
#include "methods/option_tables.hpp"

namespace plumekit::methods {

namespace {

const std::vector<std::string>& estimator_names() {
  static const std::vector<std::string> names{
      "peak mean",     "peak variance",     "peak mean x variance",
      "90% area mean", "90% area variance", "90% area mean x variance"};
  return names;
}

// 1 / the largest finite value of `g`, or 0 when there is none above 0 (a map with no gas then
// adds nothing, rather than dividing by zero).
double inverse_peak(const Grid<double>& g) {
  double top = 0.0;
  for (double x : g.values)
    if (std::isfinite(x)) top = std::max(top, x);
  return top > 0.0 ? 1.0 / top : 0.0;
}

void check_covers(const GdmMaps& maps, const Map& map) {
  const GridShape& g = maps.mean.shape;
  const double tol = map.round_off();
  if (g.size() == 0 || maps.confidence.values.size() != g.size() ||
      maps.variance.values.size() != g.size() || std::abs(g.width - map.width) > tol ||
      std::abs(g.height - map.height) > tol)
    throw InputError("apf: the maps do not cover the arena");
}

// The index of the largest finite field value among `eligible` cells; -1 when there is none.
long argmax(const Grid<double>& field, const std::vector<char>& eligible) {
  long best = -1;
  double top = -std::numeric_limits<double>::infinity();
  for (std::size_t c = 0; c < field.values.size(); ++c)
    if (eligible[c] && field.values[c] > top) top = field.values[c], best = static_cast<long>(c);
  return best;
}

}  // namespace

const char* to_string(Locality l) {
  switch (l) {
    case Locality::None:
      return "none";
    case Locality::Closest:
      return "closest";
    case Locality::MostSuggested:
      return "most-suggested";
  }
  return "?";
}

Locality parse_locality(const std::string& name) {
  if (name == "none") return Locality::None;
  if (name == "closest" || name == "a") return Locality::Closest;
  if (name == "most-suggested" || name == "b") return Locality::MostSuggested;
  throw OptionError("apf.locality",
                    "unknown locality '" + name + "'; use none, closest (a) or most-suggested (b)");
}

GdmOptions ApfOptions::default_gdm() {
  GdmOptions g;
  g.cell = 0.1;
  g.kernel_width = 0.4;
  g.sigma_omega = 1.0;
  g.wind_stretch = 0.2;
  g.background = Background::Min;
  return g;
}

const OptionTable<ApfOptions>& apf_option_table() {
  using O = ApfOptions;
  static const OptionTable<O> table{
      "Adaptive sampling for gas mapping (methods::ApfOptions; --apf-weights sets the betas)",
      {{"apf.beta_m", "", &O::beta_m, real_range(0.0, 1.0, ""),
        "Weight of the mean term (eq. 8.4; the three weights sum to 1)",
        "the seed's best is {default}"},
       {"apf.beta_v", "", &O::beta_v, real_range(0.0, 1.0, ""), "Weight of the variance term",
        "the seed's best is {default}"},
       {"apf.beta_c", "", &O::beta_c, real_range(0.0, 1.0, ""), "Weight of the confidence term",
        "the seed's best is {default}"},
       {"apf.suggestions", "", &O::suggestions, count_range(1, 10000),
        "Suggestions n_sp per decision", "the seed's n_sp is {default}"},
       {"apf.charge", "", &O::charge, real_range(-1000.0, 0.0, ""),
        "Charge q of each picked suggestion's repulsion (eq. 8.7; <= 0 repels)",
        "q <= 0 repels; the seed's is {default}"},
       {"apf.sigma_d", "", &O::sigma_d, positive(1000.0, "m"),
        "Length of the repulsion q exp(-d / sigma_d), m", "the seed's is {default} m"},
       {"apf.locality",
        "--apf-locality",
        enum_field(&O::locality, &to_string, &parse_locality, "none, closest, most-suggested"),
        {},
        "APF: which of the suggestions to take: none (the best), closest (A) or most-suggested "
        "(B)"},
       {"apf.counter_radius", "", &O::counter_radius, non_negative(100.0, "m"),
        "Locality B: neighbours counted (and reset) with a cell, m", "the seed's is {default} m"},
       {"apf.min_step", "", &O::min_step, non_negative(1000.0, "m"),
        "Cells closer than this to the robot are never suggested, m",
        "the seed's drone's is {default} m"},
       {"apf.max_steps", "", &O::max_steps, count_range(1, 1000000),
        "Stops before it gives up (the run's step budget replaces it)",
        "the seed compared runs at {default}"},
       {"apf.confidence_stop", "", &O::confidence_stop, real_range(0.0, 1.0, "", false, true),
        "Stop once the confidence exceeds this in every free cell (0: never)",
        "0 disables the stop; e.g. {default}"},
       {"apf.normalise",
        "",
        &O::normalise,
        {},
        "Scale the mean and variance maps to [0, 1] over the free cells before weighting"},
       {"apf.estimator",
        "",
        &O::estimator,
        {},
        "Which source estimate of the gas map it reports"}}};
  return table;
}

void ApfOptions::validate() const {
  const OptionTable<ApfOptions>& table = apf_option_table();
  for (const char* name : {"apf.beta_m", "apf.beta_v", "apf.beta_c"})
    validate_entry(table.entry(name), *this);
  const double sum = beta_m + beta_v + beta_c;
  if (std::abs(sum - 1.0) > 1e-6)
    throw OptionError("apf.beta_c", "beta_m + beta_v + beta_c must be 1 (seed 000 eq. 8.5), got " +
                                        compact(sum) + "; the seed's best is " + default_weights());
  plumekit::validate(table, *this);
  check_name("apf.estimator", estimator, estimator_names());
  gdm.validate();
}

std::string default_weights() {
  const ApfOptions o;
  return option_number(o.beta_m) + "," + option_number(o.beta_v) + "," + option_number(o.beta_c);
}

Grid<double> apf_field(const GdmMaps& maps, const ApfOptions& o) {
  const double sr = o.normalise ? inverse_peak(maps.mean) : 1.0;
  const double sv = o.normalise ? inverse_peak(maps.variance) : 1.0;
  Grid<double> apf(maps.mean.shape, 0.0);
  for (std::size_t c = 0; c < apf.values.size(); ++c)
    apf.values[c] = o.beta_m * sr * maps.mean.values[c] + o.beta_v * sv * maps.variance.values[c] -
                    o.beta_c * maps.confidence.values[c];  // NaN stays NaN in obstacles
  return apf;
}

std::vector<ApfSuggestion> apf_suggestions(const GdmMaps& maps, const Map& map, const ApfOptions& o,
                                           Vec2 robot) {
  check_covers(maps, map);
  Grid<double> field = apf_field(maps, o);
  const GridShape& g = field.shape;
  // Free cells at least a step from the robot; all free cells when none is that far.
  std::vector<char> eligible(g.size(), 0);
  bool any_far = false;
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      const std::size_t c = g.index(i, j);
      // 1e-9 m of slack: a cell exactly a step away stays eligible whatever the round-off.
      eligible[c] =
          std::isfinite(field.values[c]) && norm(g.centre(i, j) - robot) + 1e-9 >= o.min_step;
      any_far = any_far || eligible[c];
    }
  if (!any_far)
    for (std::size_t c = 0; c < g.size(); ++c)
      eligible[c] = std::isfinite(field.values[c]);
  std::vector<ApfSuggestion> out;
  const double strength = o.beta_c * o.charge;  // beta_C q of eq. 8.6-8.7
  for (int n = 0; n < o.suggestions; ++n) {
    const long best = argmax(field, eligible);
    if (best < 0) break;
    const int i = static_cast<int>(best % g.nx), j = static_cast<int>(best / g.nx);
    const Vec2 p = g.centre(i, j);
    out.push_back({p, i, j, field.values[best]});
    if (strength == 0.0 || n + 1 == o.suggestions) continue;
    // Eq. 8.7 read with exp(-d / sigma_d): the repulsion fades with distance (as eq. 8.12's).
    for (int jj = 0; jj < g.ny; ++jj)
      for (int ii = 0; ii < g.nx; ++ii)
        field(ii, jj) += strength * std::exp(-norm(g.centre(ii, jj) - p) / o.sigma_d);
  }
  return out;
}

SuggestionCounter::SuggestionCounter(const GridShape& shape, double radius)
    : counts_(shape, 0), radius_(radius) {}

template <class F>
void SuggestionCounter::for_each_near(Vec2 p, F&& f) {
  const GridShape& g = counts_.shape;
  if (g.size() == 0) return;
  const int pi = static_cast<int>(std::floor(p.x / g.dx()));
  const int pj = static_cast<int>(std::floor(p.y / g.dy()));
  const int i0 = std::max(0, static_cast<int>(std::floor((p.x - radius_) / g.dx())));
  const int i1 = std::min(g.nx - 1, static_cast<int>(std::floor((p.x + radius_) / g.dx())));
  const int j0 = std::max(0, static_cast<int>(std::floor((p.y - radius_) / g.dy())));
  const int j1 = std::min(g.ny - 1, static_cast<int>(std::floor((p.y + radius_) / g.dy())));
  // A little slack so that a neighbour exactly at the radius counts despite round-off.
  const double reach = radius_ + 1e-9;
  for (int j = j0; j <= j1; ++j)
    for (int i = i0; i <= i1; ++i)
      if ((i == pi && j == pj) || norm(g.centre(i, j) - p) <= reach) f(counts_(i, j));
}

void SuggestionCounter::suggest(Vec2 p) {
  for_each_near(p, [](int& s) { ++s; });
}

void SuggestionCounter::visit(Vec2 p) {
  for_each_near(p, [](int& s) { s = 0; });
}

int SuggestionCounter::count(Vec2 p) const {
  const GridShape& g = counts_.shape;
  if (g.size() == 0) return 0;
  const int i = static_cast<int>(std::floor(p.x / g.dx()));
  const int j = static_cast<int>(std::floor(p.y / g.dy()));
  return g.contains(i, j) ? counts_(i, j) : 0;
}

std::size_t choose_closest(const std::vector<ApfSuggestion>& s, Vec2 robot) {
  std::size_t best = 0;
  double nearest = norm(s.at(0).position - robot);
  // A relative margin so that equal distances computed along different axes stay a tie.
  for (std::size_t k = 1; k < s.size(); ++k) {
    const double d = norm(s[k].position - robot);
    if (d < nearest * (1.0 - 1e-12)) nearest = d, best = k;
  }
  return best;
}

std::size_t choose_most_suggested(const std::vector<ApfSuggestion>& s,
                                  const SuggestionCounter& counter, Vec2 robot) {
  const GridShape& g = counter.counts().shape;
  // A suggestion in the robot's own cell would divide by ~0: half a cell is as near as it gets.
  const double floor = 0.5 * std::min(g.dx(), g.dy());
  const auto ratio = [&](const ApfSuggestion& a) {
    return counter.count(a.position) / std::max(norm(a.position - robot), floor);
  };
  std::size_t best = 0;
  double top = ratio(s.at(0));
  for (std::size_t k = 1; k < s.size(); ++k) {
    const double r = ratio(s[k]);
    if (r > top * (1.0 + 1e-12)) top = r, best = k;
  }
  return best;
}

ApfMapping::ApfMapping(const methods::SearchArea& area, const ApfOptions& options)
    : area_(area), options_(options) {
  options_.validate();
  if (area_.map == nullptr) throw std::invalid_argument("apf: the search area has no map");
  counter_ =
      SuggestionCounter(GridShape::with_cell(area_.width(), area_.height(), options_.gdm.cell),
                        options_.counter_radius);
}

void ApfMapping::observe(const methods::Observation& o) {
  if (!is_finite(o.position) || !std::isfinite(o.gas) || !is_finite(o.wind))
    throw InputError("apf: observation " + std::to_string(samples_.size() + 1) + " is not finite");
  // The wind only matters to DM+V/W; DM+V's round kernels ignore it.
  std::optional<Vec2> wind;
  if (options_.gdm.wind_stretch > 0.0) wind = o.wind;
  samples_.push_back({o.position, o.gas, wind});
  counter_.visit(o.position);
  maps_ = kernel_dmv(*area_.map, samples_, options_.gdm);
  min_confidence_ = std::numeric_limits<double>::infinity();
  for (double a : maps_.confidence.values)
    if (std::isfinite(a)) min_confidence_ = std::min(min_confidence_, a);
}

methods::Move ApfMapping::next(Vec2 robot) {
  if (samples_.empty()) throw std::logic_error("apf: next() before the first observe()");
  suggestions_ = apf_suggestions(maps_, *area_.map, options_, robot);
  if (suggestions_.empty()) return {robot, {}, 0.0};  // no free cell at all: stay
  // S is kept whatever the locality, so that it can be shown; only B reads it.
  for (const ApfSuggestion& s : suggestions_)
    counter_.suggest(s.position);
  switch (options_.locality) {
    case Locality::None:
      chosen_ = 0;
      break;
    case Locality::Closest:
      chosen_ = choose_closest(suggestions_, robot);
      break;
    case Locality::MostSuggested:
      chosen_ = choose_most_suggested(suggestions_, counter_, robot);
      break;
  }
  return {suggestions_[chosen_].position, {}, 0.0};
}

std::optional<Vec2> ApfMapping::estimate() const {
  if (samples_.empty()) return std::nullopt;
  for (const SourceEstimate& e : source_estimates(maps_))
    if (e.name == options_.estimator) return e.position;
  return std::nullopt;
}

std::string ApfMapping::stopped_by() const {
  if (samples_.empty()) return "";
  if (options_.confidence_stop > 0.0 && min_confidence_ > options_.confidence_stop)
    return "confident";
  if (static_cast<int>(samples_.size()) >= options_.max_steps) return "max_samples";
  return "";
}

std::unique_ptr<methods::LocalizationMethod> make_apf_mapping(const methods::SearchArea& area,
                                                              const ApfOptions& options) {
  return std::make_unique<ApfMapping>(area, options);
}

MethodSpec apf_spec() {
  return {"apf",
          "adaptive sampling for gas distribution mapping (artificial potential field)",
          "seed 000 ch. 8",
          MethodTraits{false, RunEnd::OwnStopRule},
          [](const MethodOptions& o, const SearchArea& area, std::uint64_t) {
            ApfOptions apf = o.apf;
            apf.max_steps = o.tracking.max_steps;
            return make_apf_mapping(area, apf);
          },
          {}};
}

}  // namespace plumekit::methods
