#pragma once
// The STE loop turned inside out: the caller moves the robot and reads its sensors (a simulated
// world, a robot log, a live robot), the mission estimates and decides. methods::SteMethod puts it
// behind the methods' interface, which the run loop drives against the simulated world; the
// Python module lets a user drive one with their own readings.
#include <string>
#include <vector>

#include "planner/planner.hpp"
#include "ste/navigation.hpp"
#include "ste/passing_readings.hpp"
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
  // The same after teammates' samples `shared` (run/team.hpp: cooperative teams share every
  // sample; a weight below 1 is a partial sample of readings on the way) and this robot's own
  // partial samples `on_the_way` here (ste/passing_readings.hpp), which are added first, in that
  // order, with one posterior update for all. The sample budget (max_samples) counts this
  // robot's own stops only: the thesis's per-robot timeout.
  using Sample = PartialSample;
  const Posterior& add(Vec2 p, double value, const std::vector<Sample>& shared,
                       const std::vector<PartialSample>& on_the_way = {});
  // Where to sample next, seen from `robot`, and the planner's path there. InputError when the
  // mission has stopped or has no sample yet.
  planner::PlanResult next(Vec2 robot) const;
  // The same, planned as if samples had been taken at `virtual_points` reading what the current
  // belief predicts there (Estimator::predicted_reading): a collaborative robot's teammates'
  // goals (thesis ch. 13), so that it does not plan to learn what they are about to learn. The
  // posterior itself is unchanged.
  planner::PlanResult next(Vec2 robot, const std::vector<Vec2>& virtual_points) const;

  int samples() const { return estimator_.samples(); }
  int own_samples() const { return estimator_.samples() - shared_; }
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
  int shared_ = 0;  // samples from teammates
};

}  // namespace plumekit::ste
