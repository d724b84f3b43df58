#include "ste/mission.hpp"

#include <cmath>

#include "core/error.hpp"
#include "ste/localizer.hpp"

namespace plumekit::ste {

Mission::Mission(Estimator& estimator, const planner::Planner& planner, const Navigator& navigator,
                 const StopOptions& stop)
    : estimator_(estimator), planner_(planner), navigator_(navigator), stop_(stop) {
  stop_.validate();
}

const Posterior& Mission::add(Vec2 p, double value) {
  // A NaN would poison every later posterior without a word.
  if (!std::isfinite(p.x) || !std::isfinite(p.y))
    throw InputError("ste.sample.position: not a finite point");
  if (!std::isfinite(value)) throw InputError("ste.sample.reading: not a finite number");
  estimator_.add(p, value);
  posterior_ = estimator_.posterior();
  stopped_by_ = stop_reason(posterior_, estimator_.samples(), stop_);
  return posterior_;
}

planner::PlanResult Mission::next(Vec2 robot) const {
  if (samples() == 0)
    throw InputError("the mission has no sample yet: add one before asking where to go");
  if (stopped())
    throw InputError("the mission has stopped (" + stopped_by_ +
                     "): its estimate is final, there is no next goal");
  const Decision d = navigator_.decide(robot, estimator_, posterior_);
  return planner_.plan(robot, d.goal);
}

}  // namespace plumekit::ste
