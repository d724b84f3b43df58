#include "ste/mission.hpp"

#include <cmath>

#include "core/error.hpp"
#include "ste/stop_rule.hpp"

namespace plumekit::ste {

Mission::Mission(Estimator& estimator, const planner::Planner& planner, const Navigator& navigator,
                 const StopOptions& stop)
    : estimator_(estimator), planner_(planner), navigator_(navigator), stop_(stop) {
  stop_.validate();
}

namespace {

// A NaN would poison every later posterior without a word.
void check_sample(Vec2 p, double value) {
  if (!std::isfinite(p.x) || !std::isfinite(p.y))
    throw InputError("ste.sample.position: not a finite point");
  if (!std::isfinite(value)) throw InputError("ste.sample.reading: not a finite number");
}

}  // namespace

const Posterior& Mission::add(Vec2 p, double value) {
  return add(p, value, {});
}

const Posterior& Mission::add(Vec2 p, double value, const std::vector<Sample>& shared,
                              const std::vector<PartialSample>& on_the_way) {
  for (const std::vector<Sample>* samples : {&shared, &on_the_way})
    for (const Sample& s : *samples) {
      check_sample(s.position, s.value);
      check_weight(s.weight);
    }
  check_sample(p, value);
  for (const Sample& s : shared) {
    if (s.weight < 1.0) {
      estimator_.add_partial(s.position, s.value, s.weight);
      continue;
    }
    estimator_.add(s.position, s.value);
    ++shared_;
  }
  for (const PartialSample& s : on_the_way)
    estimator_.add_partial(s.position, s.value, s.weight);
  estimator_.add(p, value);
  posterior_ = estimator_.posterior();
  stopped_by_ = stop_reason(posterior_, own_samples(), stop_);
  return posterior_;
}

planner::PlanResult Mission::next(Vec2 robot) const {
  return next(robot, {});
}

planner::PlanResult Mission::next(Vec2 robot, const std::vector<Vec2>& virtual_points) const {
  if (samples() == 0)
    throw InputError("the mission has no sample yet: add one before asking where to go");
  if (stopped())
    throw InputError("the mission has stopped (" + stopped_by_ +
                     "): its estimate is final, there is no next goal");
  if (virtual_points.empty())
    return planner_.plan(robot, navigator_.decide(robot, estimator_, posterior_).goal);
  const std::unique_ptr<Estimator> planned = estimator_.clone();
  for (Vec2 p : virtual_points)
    planned->add(p, estimator_.predicted_reading(p, posterior_));
  const Posterior after = planned->posterior();
  return planner_.plan(robot, navigator_.decide(robot, *planned, after).goal);
}

}  // namespace plumekit::ste
