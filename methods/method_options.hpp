#pragma once
// The options every method factory receives (registry.hpp): the seeds' plume trackers, the
// particle filter, the APF, adaptive Levy taxis and STE in the local framework, and the run's step
// budget. Which method runs is `name`, a registry name (--method).
#include <optional>
#include <string>

#include "methods/apf_planner.hpp"
#include "methods/levy_taxis.hpp"
#include "methods/local_framework.hpp"
#include "methods/pf_method.hpp"
#include "methods/plume_tracking.hpp"

namespace plumekit::methods {

struct MethodOptions {
  // The registry's name of the method ("ste", "surge-cast", ...).
  std::string name = "ste";
  // The trackers, and the particle filter's exploration. Its max_steps is replaced by the one
  // below.
  TrackingOptions tracking;
  // Stops of a run at most; 0 (auto): two per square step of the arena (80 on the thesis's
  // 10 x 4 m with 1 m steps, 512 in the seeds' 32 x 8 m tunnel), at least 50. A tracker caught
  // in a dead end should not wander for hours of simulated time.
  int max_steps = 0;
  // max_steps with auto resolved for an arena of `area` m².
  int max_steps_in_use(double area) const;
  // The particle filter and its declaration rule; its seed and step budget are set per run (the
  // run's seed, tracking.max_steps).
  PfMethodOptions pf;
  // Unset: the seeds' best for the exploration (seed 001: (0.2, 0.8) with the pseudo-gradient,
  // (0.4, 0.9) with the predefined sweep).
  std::optional<double> pf_alpha, pf_beta;
  // Adaptive sampling for gas distribution mapping (seed 000 ch. 8; docs/methods.md); its
  // max_steps is replaced by the one above.
  ApfOptions apf;
  // Adaptive Lévy taxis (seed 004 ch. 16); its max_steps is replaced by the one above.
  LevyTaxisOptions levy;
  // STE in the local framework (seed 004 ch. 12): no map, odometry, a moving local map.
  LocalFrameworkOptions local;
  // The filter's options for `exploration`: alpha and beta resolved, the detection limit the
  // trackers' detection threshold, the step budget tracking.max_steps.
  PfMethodOptions pf_in_use(PfExploration exploration) const;
  // OptionError naming the field ("ste.method.tracking.step", ...).
  void validate() const;
};

}  // namespace plumekit::methods
