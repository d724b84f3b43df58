#include "methods/plume_tracking.hpp"

#include "methods/method_options.hpp"
#include "methods/registry.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "core/error.hpp"
#include "core/option_check.hpp"
#include "methods/option_tables.hpp"
#include "methods/wind_statistics.hpp"

namespace plumekit::methods {

namespace {

// Upwind turned 90 degrees counter-clockwise.
Vec2 left_of(Vec2 up) {
  return {-up.y, up.x};
}

// +1 when turning `from` counter-clockwise (by less than pi) leads toward `side`, else -1.
int turn_sign(Vec2 from, Vec2 side) {
  return cross(from, side) >= 0.0 ? 1 : -1;
}

// +1 when `v` lies on the left of upwind, else -1.
int side_of(Vec2 up, Vec2 v) {
  return dot(left_of(up), v) >= 0.0 ? 1 : -1;
}

const TrackingOptions& validated(const TrackingOptions& options) {
  options.validate();
  return options;
}

}  // namespace

const char* to_string(ZigzagFlip flip) {
  return flip == ZigzagFlip::OnLoss ? "loss" : "detection";
}

ZigzagFlip parse_zigzag_flip(const std::string& name) {
  if (name == "loss") return ZigzagFlip::OnLoss;
  if (name == "detection") return ZigzagFlip::OnDetection;
  throw OptionError("tracking.zigzag_flip", "expected loss or detection, got '" + name + "'");
}

const OptionTable<TrackingOptions>& tracking_option_table() {
  using O = TrackingOptions;
  const double inf = std::numeric_limits<double>::infinity();
  static const OptionTable<O> table{
      "Plume trackers (methods::TrackingOptions)",
      {{"tracking.step", "--track-step", &O::step, positive(100.0, "m"),
        "Step of the trackers and the particle filter's exploration, m (the seeds': 1)"},
       {"tracking.detection_threshold", "--detection-threshold", &O::detection_threshold,
        non_negative(inf, ""),
        "A stop detects gas above this mean reading, concentration units (trackers; the "
        "particle filter's lower detection limit)",
        "the default is {default} (concentration units)"},
       {"tracking.wall_margin", "", &O::wall_margin, non_negative(100.0, "m"),
        "Distance kept from the arena's walls: the search area is the arena shrunk by it, m"},
       {"tracking.zigzag_alpha_deg", "--zigzag-angle", &O::zigzag_alpha_deg,
        real_range(0.0, 90.0, "deg", true, true), "Zigzag legs' angle off upwind, degrees"},
       {"tracking.zigzag_flip",
        "--zigzag-flip",
        enum_field(&O::zigzag_flip, &to_string, &parse_zigzag_flip, "loss, detection"),
        {},
        "When the zigzag turns: loss (seed 002: the reading falls below the threshold) or "
        "detection (seed 000's list)"},
       {"tracking.gradient_beta_deg", "--gradient-angle", &O::gradient_beta_deg,
        real_range(0.0, 90.0, "deg"), "Pseudo-gradient's largest turn off upwind beta, degrees"},
       {"tracking.max_casts", "--max-casts", &O::max_casts, count_range(1, 1000),
        "Surge-cast: casts before it sweeps again"},
       {"tracking.max_misses", "--max-misses", &O::max_misses, count_range(1, 1000),
        "Zigzag: non-detections in a row before it sweeps again"},
       {"tracking.max_steps", "", &O::max_steps, count_range(1, 10000000),
        "Stops before a tracker gives up (the run's step budget, MethodOptions' max_steps, "
        "replaces it)"}}};
  return table;
}

void TrackingOptions::validate() const {
  plumekit::validate(tracking_option_table(), *this);
}

// ---- SearchBounds ----

SearchBounds::SearchBounds(const SearchArea& area, double margin) {
  if (area.map == nullptr) throw std::invalid_argument("SearchBounds: the search area has no map");
  const double smaller = std::min(area.width(), area.height());
  if (!(2.0 * margin < smaller))
    throw OptionError("tracking.wall_margin", "must be less than half the arena's smaller side (" +
                                                  compact(0.5 * smaller) + " m), got " +
                                                  compact(margin));
  lo_ = {margin, margin};
  hi_ = {area.width() - margin, area.height() - margin};
}

bool SearchBounds::inside(Vec2 p) const {
  // A tolerance so that a whole number of steps lands on the edge, not just past it.
  const double tol = 1e-9 * std::max({1.0, hi_.x, hi_.y});
  return p.x >= lo_.x - tol && p.x <= hi_.x + tol && p.y >= lo_.y - tol && p.y <= hi_.y + tol;
}

Vec2 SearchBounds::clamp(Vec2 p) const {
  return {std::clamp(p.x, lo_.x, hi_.x), std::clamp(p.y, lo_.y, hi_.y)};
}

Vec2 SearchBounds::centre() const {
  return 0.5 * (lo_ + hi_);
}

Vec2 SearchBounds::along(Vec2 p, Vec2 d, double length) const {
  if (!inside(p)) return clamp(p + length * d);
  double t = length;
  if (d.x > 0.0) t = std::min(t, (hi_.x - p.x) / d.x);
  if (d.x < 0.0) t = std::min(t, (lo_.x - p.x) / d.x);
  if (d.y > 0.0) t = std::min(t, (hi_.y - p.y) / d.y);
  if (d.y < 0.0) t = std::min(t, (lo_.y - p.y) / d.y);
  return clamp(p + std::max(t, 0.0) * d);
}

// ---- Sweeper ----

Sweeper::Sweeper(const SearchBounds& bounds, double step) : bounds_(bounds), step_(step) {}

Vec2 Sweeper::crosswind(Vec2 p, Vec2 up) {
  const Vec2 reference = direction_ == Vec2{} ? bounds_.centre() - p : direction_;
  const Vec2 left = left_of(up);
  direction_ = dot(left, reference) >= 0.0 ? left : -1.0 * left;
  return direction_;
}

Vec2 Sweeper::step(Vec2 p, Vec2 up) {
  const Vec2 across = p + step_ * crosswind(p, up);
  if (bounds_.inside(across)) return across;
  invert();
  const Vec2 ahead = p + step_ * up;
  if (bounds_.inside(ahead)) return ahead;
  // The search direction: toward the centre, which keeps the robot inside and off the corner.
  const Vec2 to_centre = bounds_.centre() - p;
  const double distance = norm(to_centre);
  if (distance <= step_) return bounds_.centre();
  return p + (step_ / distance) * to_centre;
}

// ---- PlumeTracker ----

PlumeTracker::PlumeTracker(const SearchArea& area, const TrackingOptions& options)
    : options_(validated(options)),
      bounds_(area, options.wall_margin),
      sweeper_(bounds_, options.step) {}

void PlumeTracker::observe(const Observation& o) {
  if (!is_finite(o.position) || !std::isfinite(o.gas) || !is_finite(o.wind))
    throw InputError(name() + ": an observation must be finite: position " + to_string(o.position) +
                     ", gas " + compact(o.gas) + ", wind " + to_string(o.wind));
  ++stops_;
  recorded_ = o.position;
  Vec2 up = upwind(o.wind);
  if (up == Vec2{})
    up = last_upwind_;  // calm: keep the last direction
  else
    last_upwind_ = up;
  if (!acquiring_) {
    goal_ = track(o, up);
  } else if (detected(o.gas)) {
    acquiring_ = false;
    goal_ = begin_tracking(o, up);
  } else {
    goal_ = sweeper_.step(o.position, up);
  }
}

Move PlumeTracker::next(Vec2 robot) {
  Move move;
  // The planned step, from where the robot stands; before any stop: measure there.
  // (Exactly the goal when the position was recorded without noise.)
  if (!goal_)
    move.goal = robot;
  else
    move.goal = robot == recorded_ ? *goal_ : robot + (*goal_ - recorded_);
  return move;
}

std::string PlumeTracker::stopped_by() const {
  return stops_ >= options_.max_steps ? "max_samples" : "";
}

Vec2 PlumeTracker::fall_back(Vec2 p, Vec2 up) {
  acquiring_ = true;
  return sweeper_.step(p, up);
}

// ---- SweepingMethod ----

SweepingMethod::SweepingMethod(const SearchArea& area, const TrackingOptions& options)
    : PlumeTracker(area, options) {}

Vec2 SweepingMethod::begin_tracking(const Observation& o, Vec2 up) {
  return fall_back(o.position, up);
}

Vec2 SweepingMethod::track(const Observation& o, Vec2 up) {
  return fall_back(o.position, up);
}

// ---- SurgeCast ----

SurgeCast::SurgeCast(const SearchArea& area, const TrackingOptions& options)
    : PlumeTracker(area, options) {}

Vec2 SurgeCast::surge(Vec2 p, Vec2 up) {
  const Vec2 ahead = p + options_.step * up;
  return bounds_.inside(ahead) ? ahead : sweeper_.step(p, up);  // at the upwind edge: search along
}

Vec2 SurgeCast::begin_tracking(const Observation& o, Vec2 up) {
  casts_ = 0;
  upwind_at_detection_ = up;
  return surge(o.position, up);
}

Vec2 SurgeCast::track(const Observation& o, Vec2 up) {
  const Vec2 p = o.position;
  if (detected(o.gas)) return begin_tracking(o, up);
  if (casts_ >= options_.max_casts) {
    casts_ = 0;
    return fall_back(p, up);
  }
  if (casts_ == 0) {
    // The plume swings with the wind about the source upwind: a counter-clockwise turn moves it
    // to the right of upwind. Below 1e-9 rad there is no turn to read.
    const double turn = wrap_angle(angle_of(up) - angle_of(upwind_at_detection_));
    if (turn > 1e-9)
      cast_side_ = -1;
    else if (turn < -1e-9)
      cast_side_ = 1;
    else
      cast_side_ = side_of(up, sweeper_.crosswind(p, up));
  } else {
    cast_side_ = -cast_side_;
  }
  ++casts_;
  const Vec2 side = static_cast<double>(cast_side_) * left_of(up);
  return bounds_.along(p, side, casts_ * options_.step);
}

// ---- Zigzag ----

Zigzag::Zigzag(const SearchArea& area, const TrackingOptions& options)
    : PlumeTracker(area, options) {}

Vec2 Zigzag::leg(Vec2 p, Vec2 up) {
  const double alpha = radians(options_.zigzag_alpha_deg);
  for (int attempt = 0; attempt < 2; ++attempt) {
    const Vec2 q = p + options_.step * rotate(up, side_ * alpha);
    if (bounds_.inside(q)) return q;
    side_ = -side_;  // the next leg would leave the area
  }
  return sweeper_.step(p, up);  // both sides leave (the upwind edge): search along it
}

Vec2 Zigzag::begin_tracking(const Observation& o, Vec2 up) {
  misses_ = 0;
  in_plume_ = true;
  side_ = side_of(up, sweeper_.crosswind(o.position, up));
  return leg(o.position, up);
}

Vec2 Zigzag::track(const Observation& o, Vec2 up) {
  const bool hit = detected(o.gas);
  misses_ = hit ? 0 : misses_ + 1;
  if (misses_ >= options_.max_misses) {
    misses_ = 0;
    return fall_back(o.position, up);
  }
  const bool flip = options_.zigzag_flip == ZigzagFlip::OnLoss ? (in_plume_ && !hit) : hit;
  in_plume_ = hit;
  if (flip) side_ = -side_;
  return leg(o.position, up);
}

// ---- PseudoGradient ----

PseudoGradient::PseudoGradient(const SearchArea& area, const TrackingOptions& options)
    : PlumeTracker(area, options) {}

Vec2 PseudoGradient::begin_tracking(const Observation& o, Vec2 up) {
  return measure_p1(o, up);  // the detecting stop is the first p1
}

Vec2 PseudoGradient::track(const Observation& o, Vec2 up) {
  return phase_ == GradientPhase::MeasureP1 ? measure_p1(o, up) : measure_p2(o, up);
}

Vec2 PseudoGradient::measure_p1(const Observation& o, Vec2 up) {
  p1_ = o.position;
  c1_ = reading(o.gas);
  upwind1_ = up;
  crosswind_ = sweeper_.crosswind(p1_, up);
  Vec2 p2 = p1_ + options_.step * crosswind_;
  if (!bounds_.inside(p2)) {
    sweeper_.invert();
    crosswind_ = -1.0 * crosswind_;
    p2 = bounds_.along(p1_, crosswind_, options_.step);
  }
  phase_ = GradientPhase::MeasureP2;
  return p2;
}

Vec2 PseudoGradient::measure_p2(const Observation& o, Vec2 up) {
  const double c2 = reading(o.gas);
  const Vec2 p2 = o.position;
  phase_ = GradientPhase::MeasureP1;
  if (c1_ == 0.0 && c2 == 0.0) {
    sweeper_.invert();
    return fall_back(p2, up);
  }
  const double beta = radians(options_.gradient_beta_deg);
  const double grad = c1_ / (c1_ + c2);  // Eq. 1
  double delta = 0.0;                    // Eq. 2, with the turn toward the higher reading
  if (c1_ > c2) {
    delta = angle_of(upwind1_) + turn_sign(upwind1_, -1.0 * crosswind_) * beta * 2.0 * (grad - 0.5);
    sweeper_.invert();
  } else if (c1_ < c2) {
    delta = angle_of(up) + turn_sign(up, crosswind_) * beta * 2.0 * (1.0 - grad - 0.5);
  } else {
    delta = circular_statistics({angle_of(upwind1_), angle_of(up)}).mean;
  }
  const Vec2 p3 = 0.5 * (p1_ + p2) + 1.5 * options_.step * heading(delta);
  return bounds_.clamp(p3);
}

// ---- factories and evaluation ----

std::vector<std::string> tracking_method_names() {
  return {"sweeping", "surge-cast", "zigzag", "pseudo-gradient"};
}

std::unique_ptr<LocalizationMethod> make_sweeping(const SearchArea& area,
                                                  const TrackingOptions& options) {
  return std::make_unique<SweepingMethod>(area, options);
}

std::unique_ptr<LocalizationMethod> make_surge_cast(const SearchArea& area,
                                                    const TrackingOptions& options) {
  return std::make_unique<SurgeCast>(area, options);
}

std::unique_ptr<LocalizationMethod> make_zigzag(const SearchArea& area,
                                                const TrackingOptions& options) {
  return std::make_unique<Zigzag>(area, options);
}

std::unique_ptr<LocalizationMethod> make_pseudo_gradient(const SearchArea& area,
                                                         const TrackingOptions& options) {
  return std::make_unique<PseudoGradient>(area, options);
}

std::unique_ptr<LocalizationMethod> make_tracking_method(const std::string& name,
                                                         const SearchArea& area,
                                                         const TrackingOptions& options) {
  if (name == "sweeping") return make_sweeping(area, options);
  if (name == "surge-cast") return make_surge_cast(area, options);
  if (name == "zigzag") return make_zigzag(area, options);
  if (name == "pseudo-gradient") return make_pseudo_gradient(area, options);
  check_name("method", name, tracking_method_names());  // throws
  return nullptr;
}

std::optional<double> distance_overhead(const std::vector<Vec2>& path, Vec2 source) {
  if (path.empty()) return std::nullopt;
  double travelled = 0.0;
  for (std::size_t k = 1; k < path.size(); ++k)
    travelled += norm(path[k] - path[k - 1]);
  const double progress = norm(path.front() - source) - norm(path.back() - source);
  if (!(progress > 0.0)) return std::nullopt;
  return travelled / progress;
}

// The trackers' registry entries: each ends in the success box downwind of the source.
namespace {

MethodSpec tracker_spec(std::string name, std::string description, std::string source,
                        std::unique_ptr<LocalizationMethod> (*make)(const SearchArea&,
                                                                    const TrackingOptions&),
                        MethodOptionsJson options_json = {}) {
  return {std::move(name),
          std::move(description),
          std::move(source),
          MethodTraits{false, RunEnd::SourceBox},
          [make](const MethodOptions& o, const SearchArea& area, std::uint64_t) {
            return make(area, o.tracking);
          },
          std::move(options_json)};
}

}  // namespace

MethodSpec sweeping_spec() {
  return tracker_spec("sweeping", "crosswind sweeps upwind until the plume is found",
                      "seed 000 Sec. 5.1.1", make_sweeping);
}

MethodSpec surge_cast_spec() {
  return tracker_spec("surge-cast", "surge upwind in the plume, cast crosswind when it is lost",
                      "seed 000 Sec. 5.1.2.1", make_surge_cast,
                      [](const MethodOptions& m, nlohmann::ordered_json& j) {
                        j["max_casts"] = m.tracking.max_casts;
                      });
}

MethodSpec zigzag_spec() {
  return tracker_spec("zigzag", "zigzag (dung beetle) legs upwind across the plume",
                      "seed 002 Sec. 3.2.2, seed 000 Sec. 5.1.2.2", make_zigzag,
                      [](const MethodOptions& m, nlohmann::ordered_json& j) {
                        const TrackingOptions& t = m.tracking;
                        j["zigzag_alpha_deg"] = t.zigzag_alpha_deg;
                        j["zigzag_flip"] =
                            t.zigzag_flip == ZigzagFlip::OnLoss ? "loss" : "detection";
                        j["max_misses"] = t.max_misses;
                      });
}

MethodSpec pseudo_gradient_spec() {
  return tracker_spec("pseudo-gradient", "two-position pseudo-gradient tracking upwind",
                      "seed 002 Sec. 3.2.3", make_pseudo_gradient,
                      [](const MethodOptions& m, nlohmann::ordered_json& j) {
                        j["gradient_beta_deg"] = m.tracking.gradient_beta_deg;
                      });
}

}  // namespace plumekit::methods
