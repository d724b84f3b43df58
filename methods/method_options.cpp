#include "methods/method_options.hpp"

#include <algorithm>
#include <cmath>

#include "core/option_check.hpp"
#include "methods/option_tables.hpp"

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

namespace {

// "0.2 with pf-gradient, 0.4 with pf-sweep": the seeds' best penalty for each exploration.
std::string per_exploration(double ParticleFilterOptions::*field) {
  return option_number(pf_options_for(PfExploration::Gradient).*field) + " with pf-gradient, " +
         option_number(pf_options_for(PfExploration::Sweep).*field) + " with pf-sweep, seed 001";
}

}  // namespace

const OptionTable<MethodOptions>& method_option_table() {
  using O = MethodOptions;
  using F = ParticleFilterOptions;
  static const OptionTable<O> table{
      "Methods' run (methods::MethodOptions)",
      {{"tracking.max_steps", "--max-steps", &O::max_steps, count_range(0, 10000000),
        "Stops of a tracker or particle filter run at most (0: two per square step of the "
        "arena, at least 50)",
        "0 means auto"},
       {"pf.alpha", "--pf-alpha",
        optional_field(&O::pf_alpha, [] { return per_exploration(&F::alpha); }), positive(1.0, ""),
        "Particle filter: penalty alpha of a particle outside the patch path envelope on a "
        "detection",
        "the seeds' best are {default}"},
       {"pf.beta", "--pf-beta",
        optional_field(&O::pf_beta, [] { return per_exploration(&F::beta); }), positive(1.0, ""),
        "Particle filter: penalty beta on a non-detection", "the seeds' best are {default}"}}};
  return table;
}

void MethodOptions::validate() const {
  validate_entry(method_option_table().entry("tracking.max_steps"), *this);
  tracking.validate();
  // Either exploration's filter (the method chooses its own: pf_method.cpp).
  pf_in_use(PfExploration::Gradient).validate();
  pf_in_use(PfExploration::Sweep).validate();
  apf.validate();
  levy.validate();
  local.validate();
}

}  // namespace plumekit::methods
