#pragma once
// The time metrics the field scores a search by (issue 47). GSL-Bench counts a run a success when
// the robot comes within 1 m of the source within 300 s; MAPIR's PMFS benchmark reports the
// mission time over the straight-line optimum at the robot's speed. plumekit records both, with
// the time to the first detection and to 0.5 m, for every run (runs.csv, summary.json, run.json).
#include <limits>
#include <vector>

#include "core/geometry.hpp"

namespace plumekit::run {

struct Step;

inline constexpr double kGslBenchRadius = 1.0;     // m
inline constexpr double kGslBenchTimeout = 300.0;  // s

// Seconds since the mission started; NaN where the run never got there.
struct MissionTimes {
  static constexpr double kNever = std::numeric_limits<double>::quiet_NaN();
  // The first reading above the detection threshold (--detection-threshold): one taken on the
  // way, or a stop's mean at the stop's end.
  double first_detection_s = kNever;
  // The first moment a robot (any of a team) is within 1 m and within 0.5 m of the source.
  double within_1m_s = kNever, within_0_5m_s = kNever;
  // The declaration, and the mission's end (LocalizationResult::time_s): the same, unless the robot
  // then drove to its estimate (--approach).
  double declared_s = 0.0, ended_s = 0.0;
  // The shortest collision-free way from the start to the source at the robot's speed (a
  // team's: its nearest robot's): the optimum a search is compared with. NaN when none.
  double optimum_s = kNever;
  // The whole mission over the optimum; NaN without an optimum.
  double over_optimum() const { return optimum_s > 0.0 ? ended_s / optimum_s : kNever; }
  // GSL-Bench's rule: within 1 m within 300 s.
  bool gsl_bench_success() const { return within_1m_s <= kGslBenchTimeout; }
};

// When a robot whose stops were `steps` first came within `radius` of `source`: it drove each
// stop's path_in at `speed` m/s, arriving at the stop's arrived_s, and stood there until its
// time_s; then, leaving its last stop, it drove `approach` (its way to its estimate after the
// method stopped; MethodRunOptions::approach). NaN when it never did.
double first_within(const std::vector<Step>& steps, Vec2 source, double radius, double speed,
                    const std::vector<Vec2>& approach = {});
// The first reading above `threshold`: one taken on the way (Step::on_the_way), or the end of a
// stop whose mean is; NaN when none is.
double first_detection(const std::vector<Step>& steps, double threshold);

}  // namespace plumekit::run
