#include "ste/localizer.hpp"

#include "ste/method_run.hpp"
#include "ste/ste_method.hpp"

namespace plumekit::ste {

std::string stop_reason(const Posterior& posterior, int samples, const StopOptions& stop) {
  if (posterior.entropy < stop.entropy_fraction * posterior.max_entropy &&
      posterior.seen_mass >= stop.seen_mass)
    return "entropy";
  return samples >= stop.max_samples_in_use() ? "max_samples" : "";
}

LocalizationResult localize(Vec2 start, Estimator& estimator, SimulatedWorld& world,
                            const planner::Planner& planner, const Navigator& navigator,
                            const StopOptions& stop, const MethodRunOptions& options) {
  SteMethod method(estimator, planner, navigator, stop);
  return run_method(start, method, world, planner, options);
}

}  // namespace plumekit::ste
