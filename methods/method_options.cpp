#include "methods/method_options.hpp"

#include <algorithm>
#include <cmath>

#include "core/option_check.hpp"

namespace plumekit::methods {

PfMethodOptions MethodOptions::pf_in_use(PfExploration exploration) const {
  PfMethodOptions o = pf;
  o.filter = pf_options_for(exploration, pf.filter);
  if (pf_alpha) o.filter.alpha = *pf_alpha;
  if (pf_beta) o.filter.beta = *pf_beta;
  o.filter.detection_limit = tracking.detection_threshold;
  o.max_steps = tracking.max_steps;
  return o;
}

int MethodOptions::max_steps_in_use(double area) const {
  if (max_steps > 0) return max_steps;
  return std::max(50, static_cast<int>(std::ceil(2.0 * area / (tracking.step * tracking.step))));
}

void MethodOptions::validate() const {
  check_count("tracking.max_steps", max_steps, 0, 10000000, "0 means auto");
  tracking.validate();
  // Either exploration's filter (the method chooses its own: pf_method.cpp).
  pf_in_use(PfExploration::Gradient).validate();
  pf_in_use(PfExploration::Sweep).validate();
  apf.validate();
  levy.validate();
  local.validate();
}

}  // namespace plumekit::methods
