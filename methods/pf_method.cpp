#include "methods/pf_method.hpp"

#include "methods/method_options.hpp"
#include "methods/plume_tracking.hpp"
#include "methods/registry.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "core/option_check.hpp"
#include "methods/option_tables.hpp"
#include "methods/wind_statistics.hpp"

namespace plumekit::methods {

namespace {

const PfMethodOptions& validated(const PfMethodOptions& options) {
  options.validate();
  return options;
}

// The stops of one line, ascending across the wind; points a round-off outside the rectangle are
// moved onto its edge.
std::vector<Vec2> line_stops(const SearchArea& area, Vec2 d, Vec2 c, double a, double b_lo,
                             int count, double step) {
  const double tol = area.map->round_off();
  std::vector<Vec2> stops;
  for (int j = 0; j <= count; ++j) {
    Vec2 q = a * d + (b_lo + j * step) * c;
    if (q.x < -tol || q.x > area.width() + tol || q.y < -tol || q.y > area.height() + tol) continue;
    q = {std::clamp(q.x, 0.0, area.width()), std::clamp(q.y, 0.0, area.height())};
    if (area.is_free(q)) stops.push_back(q);
  }
  return stops;
}

}  // namespace

ParticleFilterOptions pf_options_for(PfExploration exploration, ParticleFilterOptions base) {
  base.alpha = exploration == PfExploration::Sweep ? 0.4 : 0.2;
  base.beta = exploration == PfExploration::Sweep ? 0.9 : 0.8;
  return base;
}

const OptionTable<SweepPatternOptions>& sweep_option_table() {
  using O = SweepPatternOptions;
  static const OptionTable<O> table{
      "Predefined sweep (methods::SweepPatternOptions)",
      {{"sweep.step", "", &O::step, real_range(0.1, 100.0, "m"),
        "Spacing of the sweep's lines and of the stops on a line, m"},
       {"sweep.max_steps", "", &O::max_steps, count_range(1, 10000000),
        "Stops before the sweep gives up (the run's step budget replaces it)"}}};
  return table;
}

void SweepPatternOptions::validate() const {
  plumekit::validate(sweep_option_table(), *this);
}

std::vector<Vec2> sweep_pattern(const SearchArea& area, Vec2 start, Vec2 wind, double step) {
  const Vec2 d = norm(wind) < 1e-9 ? Vec2{1.0, 0.0} : (1.0 / norm(wind)) * wind;  // downwind
  const Vec2 c{-d.y, d.x};  // across: d turned 90 deg counter-clockwise, exactly
  double a_lo = 1e300, a_hi = -1e300, b_lo = 1e300, b_hi = -1e300;
  for (Vec2 p : {Vec2{0.0, 0.0}, Vec2{area.width(), 0.0}, Vec2{0.0, area.height()},
                 Vec2{area.width(), area.height()}}) {
    a_lo = std::min(a_lo, dot(p, d));
    a_hi = std::max(a_hi, dot(p, d));
    b_lo = std::min(b_lo, dot(p, c));
    b_hi = std::max(b_hi, dot(p, c));
  }
  const int lines = static_cast<int>(std::floor((a_hi - a_lo) / step + 1e-9));
  const int per_line = static_cast<int>(std::floor((b_hi - b_lo) / step + 1e-9));
  std::vector<Vec2> pattern;
  Vec2 last = start;
  for (int k = 0; k <= lines; ++k) {
    std::vector<Vec2> stops = line_stops(area, d, c, a_hi - k * step, b_lo, per_line, step);
    if (stops.empty()) continue;
    // Boustrophedon: each line starts at its end nearer the last stop.
    if (norm(stops.back() - last) < norm(stops.front() - last))
      std::reverse(stops.begin(), stops.end());
    pattern.insert(pattern.end(), stops.begin(), stops.end());
    last = pattern.back();
  }
  return pattern;
}

PredefinedSweep::PredefinedSweep(const SearchArea& area, const SweepPatternOptions& options)
    : area_(area), options_(options) {
  options_.validate();
}

void PredefinedSweep::observe(const Observation& o) {
  check_observation(o, "predefined-sweep");
  if (!built_) {
    pattern_ = sweep_pattern(area_, o.position, o.wind, options_.step);
    built_ = true;
  }
  ++stops_;
  awaiting_ = false;
}

Move PredefinedSweep::next(Vec2 robot) {
  while (next_ < pattern_.size() && norm(pattern_[next_] - robot) < 0.5 * options_.step)
    ++next_;
  awaiting_ = true;
  if (next_ >= pattern_.size()) return Move{robot, {}, 0.0};
  return Move{pattern_[next_++], {}, 0.0};
}

std::string PredefinedSweep::stopped_by() const {
  if (built_ && next_ >= pattern_.size() && !awaiting_) return "swept";
  if (stops_ >= options_.max_steps) return "max_samples";
  return "";
}

const OptionTable<PfMethodOptions>& pf_method_option_table() {
  using O = PfMethodOptions;
  static const OptionTable<O> table{
      "Particle filter's declaration (methods::PfMethodOptions)",
      {{"pf.declare_iterations", "--declare-iterations", &O::declare_iterations,
        count_range(0, 1000000),
        "Particle filter: declare when the estimate stayed within --declare-radius this many "
        "iterations (0: never; Li et al.'s 20)",
        "e.g. 20 (Li et al.); 0, the default, never declares"},
       {"pf.declare_radius", "--declare-radius", &O::declare_radius, positive(1000.0, "m"),
        "Particle filter: the declaration's radius, m"},
       {"pf.max_steps", "", &O::max_steps, count_range(1, 10000000),
        "Stops before the filter gives up (the run's step budget replaces it)"}}};
  return table;
}

void PfMethodOptions::validate() const {
  filter.validate();
  plumekit::validate(pf_method_option_table(), *this);
}

ParticleFilterMethod::ParticleFilterMethod(const SearchArea& area,
                                           std::unique_ptr<LocalizationMethod> explorer,
                                           const PfMethodOptions& options, std::string name)
    : options_(validated(options)),
      filter_(area, options_.filter, options_.seed),
      explorer_(std::move(explorer)),
      name_(std::move(name)) {
  if (!explorer_) throw std::invalid_argument("ParticleFilterMethod: no explorer");
  if (name_.empty()) name_ = "pf-" + explorer_->name();
}

void ParticleFilterMethod::observe(const Observation& o) {
  check_observation(o, "pf");
  filter_.update(o);
  explorer_->observe(o);
  ++steps_;
  if (filter_.last_step().detection) detected_ = true;
  const int k = options_.declare_iterations;
  if (!detected_ || k == 0) return;
  recent_.push_back(filter_.estimate());
  if (static_cast<int>(recent_.size()) > k) recent_.pop_front();
  if (static_cast<int>(recent_.size()) < k) return;
  const Vec2 newest = recent_.back();
  declared_ = std::all_of(recent_.begin(), recent_.end(),
                          [&](Vec2 p) { return norm(p - newest) <= options_.declare_radius; });
}

std::optional<Vec2> ParticleFilterMethod::estimate() const {
  if (steps_ == 0) return std::nullopt;
  return filter_.estimate();
}

std::string ParticleFilterMethod::stopped_by() const {
  if (declared_) return "declared";
  if (explorer_->stopped()) return explorer_->stopped_by();
  if (steps_ >= options_.max_steps) return "max_samples";
  return "";
}

std::unique_ptr<LocalizationMethod> make_pf_sweep(const SearchArea& area,
                                                  const PfMethodOptions& options,
                                                  const SweepPatternOptions& sweep) {
  return std::make_unique<ParticleFilterMethod>(
      area, std::make_unique<PredefinedSweep>(area, sweep), options, "pf-sweep");
}

std::optional<Grid<double>> ParticleFilterMethod::belief_map(const Map& map) const {
  Grid<double> g(GridShape::with_cell(map.width, map.height, 0.1), 0.0);
  const auto& p = filter_.particles();
  for (std::size_t k = 0; k < p.size(); ++k) {
    const int i = std::clamp(static_cast<int>(p[k].x / g.shape.dx()), 0, g.shape.nx - 1);
    const int j = std::clamp(static_cast<int>(p[k].y / g.shape.dy()), 0, g.shape.ny - 1);
    g(i, j) += filter_.weights()[k];
  }
  return g;
}

namespace {

// The filter's options a run records (after the explorer's).
void pf_options_json(const PfMethodOptions& pf, nlohmann::ordered_json& j) {
  j["particles"] = pf.filter.particles;
  j["pf_alpha"] = pf.filter.alpha;
  j["pf_beta"] = pf.filter.beta;
  j["declare_radius_m"] = pf.declare_radius;
  j["declare_iterations"] = pf.declare_iterations;
}

}  // namespace

// The particle filter's registry entries: the filter declares the source itself (its own stop
// rule), explored by the pseudo-gradient tracker or the predefined sweep.
MethodSpec pf_gradient_spec() {
  return {"pf-gradient",
          "particle filter explored by the pseudo-gradient tracker",
          "seed 001 Sec. III, seed 002",
          MethodTraits{false, RunEnd::OwnStopRule},
          [](const MethodOptions& o, const SearchArea& area, std::uint64_t seed) {
            PfMethodOptions pf = o.pf_in_use(PfExploration::Gradient);
            pf.seed = seed;
            return std::make_unique<ParticleFilterMethod>(
                area, make_pseudo_gradient(area, o.tracking), pf, "pf-gradient");
          },
          [](const MethodOptions& m, nlohmann::ordered_json& j) {
            j["gradient_beta_deg"] = m.tracking.gradient_beta_deg;
            pf_options_json(m.pf_in_use(PfExploration::Gradient), j);
          }};
}

MethodSpec pf_sweep_spec() {
  return {"pf-sweep",
          "particle filter explored by a predefined sweep",
          "seed 001 Sec. III, seed 000 Sec. 6.2.1",
          MethodTraits{false, RunEnd::OwnStopRule},
          [](const MethodOptions& o, const SearchArea& area, std::uint64_t seed) {
            PfMethodOptions pf = o.pf_in_use(PfExploration::Sweep);
            pf.seed = seed;
            auto sweep = std::make_unique<PredefinedSweep>(
                area, SweepPatternOptions{o.tracking.step, o.tracking.max_steps});
            return std::make_unique<ParticleFilterMethod>(area, std::move(sweep), pf, "pf-sweep");
          },
          [](const MethodOptions& m, nlohmann::ordered_json& j) {
            pf_options_json(m.pf_in_use(PfExploration::Sweep), j);
          }};
}

}  // namespace plumekit::methods
