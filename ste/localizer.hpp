#pragma once
// The STE loop (thesis ch. 7): sample, update the posterior, stop when it is
// certain (entropy below a fraction of its maximum) or after max_samples,
// else choose the next sampling point and travel there along a planner path
// while the world's plume runs on. The declared source is the posterior's
// expected value.
#include <limits>
#include <string>
#include <vector>

#include "planner/planner.hpp"
#include "ste/navigation.hpp"
#include "ste/posterior.hpp"
#include "ste/world.hpp"

namespace plumekit::ste {

struct StopOptions {
  double entropy_fraction = 0.02;  // stop below 2 % of the maximum entropy
  // ... and only when at least this share of the posterior's mass is on sources the samples
  // could tell from no source (Posterior::seen_mass): a certain posterior on sources whose plume
  // reaches no sample says only that nothing was read.
  double seen_mass = 0.95;
  // 0 (auto): the thesis's 50, or on a floor (the floor mode) one sample per 10 m² of its
  // reachable free space when that is more (Scenario resolves it; resolve_max_samples).
  int max_samples = kAutoMaxSamples;
  static constexpr int kAutoMaxSamples = 0;
  static constexpr int kThesisMaxSamples = 50;
  int max_samples_in_use() const {
    return max_samples == kAutoMaxSamples ? kThesisMaxSamples : max_samples;
  }
  // OptionError naming the field (ste/README.md, "Options"); ste/options.cpp.
  void validate() const;
};

struct Step {
  Vec2 position;            // where the sample was taken
  Vec2 recorded;            // where the robot recorded it (position noise), what the estimator saw
  double value = 0.0;       // its mean concentration
  Vec2 wind;                // the anemometer's mean wind there
  double time_s = 0.0;      // simulated time since the robot started, at the sample's end
  double distance_m = 0.0;  // travelled before it
  Vec2 estimate, map;       // posterior after it
  double entropy = 0.0;
  double compute_s = 0.0;     // estimation + navigation + planning after this sample
  std::vector<Vec2> path_in;  // the path that led here (empty for the first)
};

// One robot of a team (ste/team.hpp).
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
  double time_s = 0.0;     // simulated mission time
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
  Posterior posterior;  // STE's; empty for the other methods
  // A team's run (ste/team.hpp): every robot, and which one's estimate the team declares (the
  // run's steps and posterior are that robot's; samples and distance are summed over the team,
  // time_s runs until the declaration). Empty and -1 for a robot alone.
  std::vector<TeamRobot> team;
  int declared_by = -1;
  std::string strategy;  // the team's (TeamStrategy), "" alone
};

// Why the run stops after `samples` samples with this posterior: "entropy", "max_samples", or ""
// (it goes on).
std::string stop_reason(const Posterior& posterior, int samples, const StopOptions& stop);

struct MethodRunOptions;  // method_run.hpp

// run_method (method_run.hpp) with STE (SteMethod) on `estimator`, which plans its own paths;
// `options` may end the run on arrival (its disc).
LocalizationResult localize(Vec2 start, Estimator& estimator, SimulatedWorld& world,
                            const planner::Planner& planner, const Navigator& navigator,
                            const StopOptions& stop, const MethodRunOptions& options);

}  // namespace plumekit::ste
