#pragma once
// What a run records: every stop of its robot(s) (Step), a team's robots (TeamRobot) and the
// result a report and its pictures are made from (LocalizationResult).
#include <limits>
#include <string>
#include <vector>

#include "core/geometry.hpp"
#include "run/mission_times.hpp"
#include "ste/posterior.hpp"

namespace plumekit::run {

// A reading taken on the way to a stop (WorldOptions::read_while_moving).
struct PassingRecord {
  Vec2 position;        // the true point
  Vec2 recorded;        // where the robot recorded it
  double time_s = 0.0;  // since the robot started
  double value = 0.0;
};

struct Step {
  Vec2 position;            // where the sample was taken
  Vec2 recorded;            // where the robot recorded it (position noise), what the estimator saw
  double value = 0.0;       // its mean concentration
  Vec2 wind;                // the anemometer's mean wind there
  double time_s = 0.0;      // simulated time since the robot started, at the sample's end
  double arrived_s = 0.0;   // ... when the robot arrived there and the sample began
  double distance_m = 0.0;  // travelled before it
  Vec2 estimate, map;       // posterior after it
  double entropy = 0.0;
  double compute_s = 0.0;                 // estimation + navigation + planning after this sample
  std::vector<Vec2> path_in;              // the path that led here (empty for the first)
  std::vector<PassingRecord> on_the_way;  // the readings taken along it, oldest first
};

// One robot of a team (run/team.hpp).
struct TeamRobot {
  Vec2 start;
  std::vector<Step> steps;  // its own stops
  double distance_m = 0.0;
  // "entropy" (it declared), "max_samples" (its own budget ran out), or "" (the team stopped
  // before it did).
  std::string stopped_by;
  Vec2 estimate;          // its posterior's expected source at its last stop
  double entropy = 0;     // of its last posterior
  int swaps = 0;          // goals it took from a teammate (collaborative task swaps)
  double waited_s = 0.0;  // kept waiting by the separation rule
  // Its closest approach to a teammate over the run, m (infinite alone): at least the team's
  // separation unless the robots started closer.
  double closest_m = std::numeric_limits<double>::infinity();
};

struct LocalizationResult {
  std::string method = "ste";  // the localization method's name (--method)
  Vec2 start;
  // Declared: STE's expected value, the particle filter's estimate, or where a plume tracker
  // ended.
  Vec2 estimate;
  std::vector<double> expected;
  Vec2 map;
  int samples = 0;
  double distance_m = 0.0;
  double time_s = 0.0;  // simulated mission time (with an approach, until it arrives)
  MissionTimes times;   // the field's time metrics (Scenario::run fills them)
  // After the method stopped, the robot's way to its estimate (MethodRunOptions::approach, issue
  // 47) and how long it drove; empty and 0 without one.
  std::vector<Vec2> approach;
  double approach_s = 0.0;
  double compute_s = 0.0;  // total decision compute (thread CPU time)
  // Wall-clock seconds: the decisions (estimation, navigation, planning), the simulated world (its
  // plume's spin-up and steps and the sensors' readings, SimulatedWorld::busy_s; for a robot of a
  // plume shared between threads, its waits for the others too) and the whole run, which holds
  // both: what a run's report adds up with the scenario's wind and model build.
  double decisions_s = 0.0, plume_s = 0.0, run_s = 0.0;
  double median_step_s = 0.0;  // median compute per decision step
  // "entropy" or "max_samples" (STE); "declared" (particle filter); "reached" (a stop in the
  // plume trackers' source box); ...
  std::string stopped_by;
  bool reached = false;  // stopped in the source box (SourceBox, method_run.hpp)
  std::vector<Step> steps;
  ste::Posterior posterior;  // STE's; empty for the other methods
  // A team's run (run/team.hpp): every robot, and which one's estimate the team declares (the
  // run's steps and posterior are that robot's; samples and distance are summed over the team,
  // time_s runs until the declaration). Empty and -1 for a robot alone.
  std::vector<TeamRobot> team;
  int declared_by = -1;
  std::string strategy;  // the team's (TeamStrategy), "" alone
};

}  // namespace plumekit::run
