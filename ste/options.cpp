// The range checks of STE's own options structs. Field names are the options' dotted paths under
// "ste."; the physics model's advection-diffusion checks its own fields.
#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "core/option_check.hpp"
#include "ste/gaussian_plume.hpp"
#include "ste/grid_estimator.hpp"
#include "ste/mh_estimator.hpp"
#include "ste/navigation.hpp"
#include "ste/physics_plume.hpp"
#include "ste/stop_rule.hpp"

namespace plumekit::ste {
void LikelihoodOptions::validate() const {
  check_non_negative("ste.likelihood.sigma_m", sigma_m, 1e9, "concentration units",
                     "the thesis uses 30");
  check_non_negative("ste.likelihood.sigma_d", sigma_d, 1e9, "concentration units",
                     "0 in simulation, 125 in the thesis's wind tunnel");
  if (!(variance() > 0.0))
    throw OptionError("ste.likelihood.sigma_m",
                      "sigma_m and sigma_d are both 0, so no reading could differ from the "
                      "model; give either a positive value (the thesis uses sigma_m 30)");
  check_non_negative("ste.likelihood.sigma_rel", sigma_rel, 100.0, "", "0 means none");
  check_non_negative("ste.likelihood.sigma_std", sigma_std, 100.0, "", "0 means none");
}

void BinOptions::validate() const {
  check_positive("ste.bins.x", x, 100.0, "m", "the thesis's bins are 0.5 m");
  check_positive("ste.bins.y", y, 100.0, "m", "the thesis's bins are 0.2 m");
}

void MhOptions::validate() const {
  check_count("ste.mh.iterations", iterations, 1, 100'000'000, "the default is 4000");
  check_count("ste.mh.burn_in", burn_in, 0, iterations - 1LL,
              "it must be less than ste.mh.iterations; the default is 1000");
  check_positive("ste.mh.proposal", proposal, 1.0, "of each parameter's range",
                 "the default is 0.05");
}

void NavigationOptions::validate() const {
  check_positive("ste.navigation.step", step, 100.0, "m", "the default is 0.5 m");
  check_count("ste.navigation.lattice", lattice, 1, 20, "the default is 2 (5 x 5 candidates)");
  check_non_negative("ste.navigation.alpha", alpha, 1.0, "", "the default is 0.5");
  check_non_negative("ste.navigation.beta", beta, 1.0, "", "the default is 0.75");
  check_positive("ste.navigation.floor_spacing", floor_spacing, 100.0, "m", "the default is 1 m");
  check_count("ste.navigation.floor_gain_cells", floor_gain_cells, 16, 1'000'000,
              "the default is 512");
}

void StopOptions::validate() const {
  // 1 or more stops after the first sample (a test uses it).
  check_non_negative("ste.stop.entropy_fraction", entropy_fraction, 100.0, "",
                     "the default is 0.02; 1 or more stops after the first sample");
  check_non_negative("ste.stop.seen_mass", seen_mass, 1.0, "",
                     "the default is 0.95; 0 declares unseen sources too");
  check_count("ste.stop.max_samples", max_samples, 0, 100'000,
              "the default is 0 (auto: 50, more on large floors)");
}

void PhysicsPlumeOptions::validate() const {
  check_positive("ste.physics.source_cell", source_cell, 10.0, "m", "the default is 0.1 m");
  advection_diffusion.validate();
  check_positive("ste.physics.scale_lo", scale_lo, 1e6, "", "1 is the dataset's release rate");
  check_range("ste.physics.scale_hi", scale_hi, scale_lo, 1e6, "",
              "it must be at least ste.physics.scale_lo");
}

void GaussianPlumeBounds::validate() const {
  check_positive("ste.gaussian.q_max", q_max, 1e12, "", "the default is 10000");
  check_positive("ste.gaussian.a_min", a_min, 10.0, "", "the default is 0.01");
  check_range("ste.gaussian.a_max", a_max, a_min, 10.0, "", "it must be at least a_min");
  check_positive("ste.gaussian.b_min", b_min, 100.0, "m", "the default is 0.02 m");
  check_range("ste.gaussian.b_max", b_max, b_min, 100.0, "m", "it must be at least b_min");
}

}  // namespace plumekit::ste
