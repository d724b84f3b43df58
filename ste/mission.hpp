#pragma once
// The STE loop turned inside out: the caller moves the robot and reads its sensors (a simulated
// world, a robot log, a live robot), the mission estimates and decides. localize() drives one
// against the simulated world; the Python module lets a user drive one with their own readings.
#include <string>

#include "planner/planner.hpp"
#include "ste/navigation.hpp"
#include "ste/posterior.hpp"

namespace plumekit::ste {

struct StopOptions;

class Mission {
 public:
  // Keeps references: every argument must outlive the mission.
  Mission(Estimator& estimator, const planner::Planner& planner, const Navigator& navigator,
          const StopOptions& stop);

  // A sample: the mean reading `value` recorded at `p` (arena frame). Updates the posterior and
  // the stop rule; returns the posterior. InputError for a point or value that is not finite.
  const Posterior& add(Vec2 p, double value);
  // Where to sample next, seen from `robot`, and the planner's path there. InputError when the
  // mission has stopped or has no sample yet.
  planner::PlanResult next(Vec2 robot) const;

  int samples() const { return estimator_.samples(); }
  const Posterior& posterior() const { return posterior_; }
  // "entropy", "max_samples", or "" while the mission goes on (stop_reason, localizer.hpp).
  const std::string& stopped_by() const { return stopped_by_; }
  bool stopped() const { return !stopped_by_.empty(); }

 private:
  Estimator& estimator_;
  const planner::Planner& planner_;
  const Navigator& navigator_;
  const StopOptions& stop_;
  Posterior posterior_;
  std::string stopped_by_;
};

}  // namespace plumekit::ste
