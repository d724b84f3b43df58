#include "methods/crosswind_search.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "core/error.hpp"
#include "core/option_check.hpp"
#include "core/statistics.hpp"
#include "methods/levy_taxis.hpp"
#include "methods/option_tables.hpp"
#include "methods/registry.hpp"

namespace plumekit::methods {

namespace {

constexpr double kWallMargin = 0.05;  // m kept between a goal and each wall

// Eq. 17.3's arc length from t = 0: the Archimedean spiral r = a theta, a = s_d / (2 pi).
double spiral_arc(double t, double drift) {
  const double theta = 2.0 * kPi * t;
  return drift / (4.0 * kPi) * (theta * std::sqrt(1.0 + theta * theta) + std::asinh(theta));
}

void check_finite(double value, const char* field) {
  if (!std::isfinite(value))
    throw InputError(std::string("crosswind search: observation.") + field + " is not finite");
}

}  // namespace

const OptionTable<CrosswindSearchOptions>& crosswind_search_option_table() {
  using O = CrosswindSearchOptions;
  const double inf = std::numeric_limits<double>::infinity();
  static const OptionTable<O> table{
      "The tunnel's trackers (methods::CrosswindSearchOptions)",
      {{"tunnel.search.step", "", &O::step, positive(10.0, "m"),
        "Travel per decision, m (the thesis's 50 mm/s for 1 s)",
        "the thesis's 50 mm/s for 1 s: {default} m"},
       {"tunnel.search.levy_mu", "", &O::levy_mu, real_range(1.0, 3.0, "", true),
        "Exponent mu of the Lévy walk's moves (seed 004 Eq. 17.1)",
        "1 < mu <= 3; the thesis's {default}"},
       {"tunnel.search.levy_min", "", &O::levy_min, positive(100.0, "m"),
        "Shortest Lévy move L_min, m", "the thesis's {default} m"},
       {"tunnel.search.levy_max",
        "",
        &O::levy_max,
        {},
        "Longest Lévy move (longer draws are cut to it), m",
        "",
        "more than tunnel.search.levy_min, at most 1000 m"},
       {"tunnel.search.spiral_drift", "", &O::spiral_drift, positive(10.0, "m"),
        "Radius the spiral gains per turn s_d, m (seed 004 Eq. 17.3)",
        "the default is {default} m per turn"},
       {"tunnel.search.cast", "", &O::cast, positive(100.0, "m"), "Cast width D_cast, m",
        "the thesis's {default} m"},
       {"tunnel.search.threshold", "--threshold", &O::threshold, real_range(0.0, 1.0, "", true),
        "Trackers: the share of the first readings taken as in the plume (Table 17.1: 0.7 or "
        "0.9)",
        "the thesis's 0.7 or 0.9"},
       {"tunnel.search.calibration", "", &O::calibration, count_range(1, 1000000),
        "Readings that set the in-plume threshold"},
       {"tunnel.search.detection", "", &O::detection, positive(inf, "concentration units"),
        "The lowest reading that counts as gas, concentration units"},
       {"tunnel.search.altitude", "", &O::altitude, real_range(-1e6, 1e6, "m"),
        "Cast2d: the height the robot flies at, m (the runner sets it)",
        "a height inside the tunnel"}}};
  return table;
}

void CrosswindSearchOptions::validate() const {
  const OptionTable<CrosswindSearchOptions>& table = crosswind_search_option_table();
  for (const char* name : {"tunnel.search.step", "tunnel.search.levy_mu", "tunnel.search.levy_min"})
    validate_entry(table.entry(name), *this);
  check_range("tunnel.search.levy_max", levy_max, levy_min, 1000.0, "m",
              "it must exceed tunnel.search.levy_min; the default is " +
                  default_text(table.entry("tunnel.search.levy_max")) + " m",
              true);
  for (const char* name :
       {"tunnel.search.spiral_drift", "tunnel.search.cast", "tunnel.search.threshold",
        "tunnel.search.calibration", "tunnel.search.detection", "tunnel.search.altitude"})
    validate_entry(table.entry(name), *this);
}

CrosswindSearch::CrosswindSearch(const Box3& tunnel, const CrosswindSearchOptions& options,
                                 std::uint64_t seed)
    : tunnel_(tunnel), options_(options), rng_(seed), threshold_(options.detection) {
  options_.validate();
  if (!is_finite(tunnel.lo) || !is_finite(tunnel.hi) || tunnel.hi.x < tunnel.lo.x ||
      tunnel.hi.y < tunnel.lo.y || tunnel.hi.z < tunnel.lo.z)
    throw InputError("crosswind search: the tunnel must be a finite box with hi >= lo");
  if (options_.mode == CrosswindMode::Cast2d &&
      (options_.altitude < tunnel.lo.z || options_.altitude > tunnel.hi.z))
    throw OptionError("tunnel.search.altitude", "must lie inside the tunnel's heights, got " +
                                                    compact(options_.altitude) + " m");
  const auto shrink = [](double& lo, double& hi) {
    const double m = std::min(kWallMargin, 0.5 * (hi - lo));
    lo += m;
    hi -= m;
  };
  inner_ = tunnel_;
  shrink(inner_.lo.x, inner_.hi.x);
  shrink(inner_.lo.y, inner_.hi.y);
  shrink(inner_.lo.z, inner_.hi.z);
}

double CrosswindSearch::uniform01() {
  return static_cast<double>(rng_() >> 11) * 0x1.0p-53;
}

Vec3 CrosswindSearch::clamp_inside(Vec3 p) const {
  return inner_.clamp(p);
}

Vec3 CrosswindSearch::toward(Vec3 robot, Vec3 goal) const {
  const bool flat = options_.mode == CrosswindMode::Cast2d;
  if (flat) robot.z = goal.z = options_.altitude;
  goal = clamp_inside(goal);
  const double d = norm(goal - robot);
  // The clamp is non-expansive, so this only bites when the robot stands within the margin.
  if (d > options_.step) goal = robot + (options_.step / d) * (goal - robot);
  // A robot outside the tunnel is brought back in, whatever the step.
  goal = tunnel_.clamp(goal);
  if (flat) goal.z = options_.altitude;
  return goal;
}

bool CrosswindSearch::arrived(Vec3 robot) const {
  if (options_.mode == CrosswindMode::Cast2d) robot.z = options_.altitude;
  return norm(waypoint_ - robot) <= 0.1 * options_.step;
}

void CrosswindSearch::observe(const Observation3& o) {
  check_finite(o.position.x, "position.x");
  check_finite(o.position.y, "position.y");
  check_finite(o.position.z, "position.z");
  check_finite(o.gas, "gas");
  check_finite(o.wind.x, "wind.x");
  check_finite(o.wind.y, "wind.y");
  check_finite(o.wind.z, "wind.z");
  check_finite(o.wind_variance, "wind_variance");
  check_finite(o.time_s, "time_s");
  if (o.gas < 0.0)
    throw InputError("crosswind search: observation.gas is negative (" + compact(o.gas) + ")");

  const bool flat = options_.mode == CrosswindMode::Cast2d;
  if (!calibrated_ && o.gas >= options_.detection) {
    calibration_readings_.push_back(o.gas);
    if (static_cast<int>(calibration_readings_.size()) == options_.calibration) {
      threshold_ =
          std::max(options_.detection, percentile(calibration_readings_, 1.0 - options_.threshold));
      calibrated_ = true;
      calibration_readings_.clear();
    }
  }

  Vec3 wind = o.wind;
  if (flat) wind.z = 0.0;
  const double speed = norm(wind);
  upwind_ = speed > 1e-9 ? (-1.0 / speed) * wind : Vec3{-1.0, 0.0, 0.0};

  if (o.gas >= threshold_) {
    phase_ = Phase::Surge;
    has_waypoint_ = false;
  } else if (phase_ == Phase::Surge) {
    loss_ = o.position;
    if (flat) loss_.z = options_.altitude;
    waypoint_ = clamp_inside(loss_);
    has_waypoint_ = true;
    t_ = 0.0;
    leg_ = 0;
    phase_ = flat ? Phase::Cast : Phase::Spiral;
  }
}

void CrosswindSearch::draw_levy_target(Vec3 robot) {
  const double length =
      levy_move_length(1.0 - uniform01(), options_.levy_mu, options_.levy_min, options_.levy_max);
  if (options_.mode == CrosswindMode::Cast2d) {
    const double side = (rng_() >> 63) ? 1.0 : -1.0;
    waypoint_ = {robot.x, robot.y + side * length, options_.altitude};
  } else {
    const double angle = 2.0 * kPi * uniform01();
    waypoint_ = {robot.x, robot.y + length * std::sin(angle), robot.z + length * std::cos(angle)};
  }
  waypoint_ = clamp_inside(waypoint_);
  has_waypoint_ = true;
}

void CrosswindSearch::advance_spiral() {
  // Solve spiral_arc(t') = spiral_arc(t) + step by Newton: the arc is convex in t, so the first
  // guess (the tangent at t) lies beyond the root and the iterates fall onto it from above.
  const double s_d = options_.spiral_drift;
  const double target = spiral_arc(t_, s_d) + options_.step;
  double t = t_;
  for (int k = 0; k < 50; ++k) {
    const double theta = 2.0 * kPi * t;
    const double f = spiral_arc(t, s_d) - target;
    const double next = t - f / (s_d * std::sqrt(1.0 + theta * theta));
    if (std::abs(next - t) <= 1e-14 * std::max(1.0, t)) {
      t = next;
      break;
    }
    t = next;
  }
  t_ = t;
  const double r = s_d * t_;
  waypoint_ = clamp_inside(
      {loss_.x, loss_.y + r * std::cos(2.0 * kPi * t_), loss_.z + r * std::sin(2.0 * kPi * t_)});
}

std::string CrosswindSearch::name() const {
  return options_.mode == CrosswindMode::Spiral3d ? "surge-spiral" : "surge-cast-2d";
}

Move3 CrosswindSearch::next(Vec3 robot) {
  if (!is_finite(robot)) throw InputError("crosswind search: the robot's position is not finite");
  switch (phase_) {
    case Phase::Surge:
      return Move3::to(toward(robot, robot + options_.step * upwind_));
    case Phase::Levy:
      if (!has_waypoint_ || arrived(robot)) draw_levy_target(robot);
      break;
    case Phase::Spiral:
      if (arrived(robot)) advance_spiral();
      break;
    case Phase::Cast:
      if (arrived(robot)) {
        ++leg_;
        const double side = leg_ % 2 == 1 ? 1.0 : -1.0;
        waypoint_ = clamp_inside({loss_.x, loss_.y + side * leg_ * options_.cast, loss_.z});
      }
      break;
  }
  return Move3::to(toward(robot, waypoint_));
}

namespace {

TunnelMethodFactory crosswind_factory(CrosswindMode mode) {
  return [mode](const TunnelMethodInputs& in) {
    CrosswindSearchOptions o = in.search;
    o.mode = mode;
    return std::make_unique<CrosswindSearch>(in.tunnel, o, in.walk_seed);
  };
}

}  // namespace

TunnelMethodSpec surge_spiral_spec() {
  return {"surge-spiral", "3-D surge-spiral plume tracker",          "seed 004 ch. 17", true,
          false,          crosswind_factory(CrosswindMode::Spiral3d)};
}

TunnelMethodSpec surge_cast_2d_spec() {
  return {"surge-cast-2d",
          "2-D surge-cast baseline flown at a fixed altitude",
          "seed 004 ch. 17, after Rahbar et al. 2017",
          true,
          true,
          crosswind_factory(CrosswindMode::Cast2d)};
}

std::string CrosswindSearch::phase() const {
  switch (phase_) {
    case Phase::Levy:
      return "levy";
    case Phase::Surge:
      return "surge";
    case Phase::Spiral:
      return "spiral";
    case Phase::Cast:
      return "cast";
  }
  return "";
}

}  // namespace plumekit::methods
