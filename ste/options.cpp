// The options tables of STE's own options structs (ste/option_tables.hpp) and their checks. Field
// names are the options' dotted paths under "ste."; the physics model's advection-diffusion checks
// its own fields. A check between two fields (burn-in below the iterations, an upper bound above
// its lower) is written here, after the table's own.
#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.hpp"
#include "core/option_check.hpp"
#include "ste/gaussian_plume.hpp"
#include "ste/grid_estimator.hpp"
#include "ste/mh_estimator.hpp"
#include "ste/navigation.hpp"
#include "ste/option_tables.hpp"
#include "ste/physics_plume.hpp"
#include "ste/stop_rule.hpp"

namespace plumekit::ste {

const OptionTable<LikelihoodOptions>& likelihood_option_table() {
  using O = LikelihoodOptions;
  static const OptionTable<O> table{
      "STE likelihood (ste::LikelihoodOptions)",
      {{"ste.likelihood.sigma_m", "", &O::sigma_m, non_negative(1e9, "concentration units"),
        "Model error, concentration units (localize's --sigma-m: one per plume model, "
        "run::default_likelihood)",
        "the thesis uses 30"},
       {"ste.likelihood.sigma_d", "", &O::sigma_d, non_negative(1e9, "concentration units"),
        "Measurement error, concentration units",
        "0 in simulation, 125 in the thesis's wind tunnel"},
       {"ste.likelihood.sigma_rel", "", &O::sigma_rel, non_negative(100.0, ""),
        "Model error relative to the predicted concentration (0: none)", "0 means none"},
       {"ste.likelihood.sigma_std", "", &O::sigma_std, non_negative(100.0, ""),
        "Model error in units of the surrogate's predicted std of the readings (0: none)",
        "0 means none"}}};
  return table;
}

void LikelihoodOptions::validate() const {
  plumekit::validate(likelihood_option_table(), *this);
  if (!(variance() > 0.0))
    throw OptionError("ste.likelihood.sigma_m",
                      "sigma_m and sigma_d are both 0, so no reading could differ from the "
                      "model; give either a positive value (the thesis uses sigma_m 30)");
}

const OptionTable<BinOptions>& bin_option_table() {
  using O = BinOptions;
  static const OptionTable<O> table{"STE entropy bins (ste::BinOptions)",
                                    {{"ste.bins.x", "", &O::x, positive(100.0, "m"),
                                      "Bin width in x, m", "the thesis's bins are 0.5 m"},
                                     {"ste.bins.y", "", &O::y, positive(100.0, "m"),
                                      "Bin height in y, m", "the thesis's bins are 0.2 m"}}};
  return table;
}

void BinOptions::validate() const {
  plumekit::validate(bin_option_table(), *this);
}

const OptionTable<MhOptions>& mh_option_table() {
  using O = MhOptions;
  static const OptionTable<O> table{
      "STE Metropolis-Hastings (ste::MhOptions)",
      {{"ste.mh.iterations", "", &O::iterations, count_range(1, 100'000'000),
        "Iterations per decision step"},
       {"ste.mh.burn_in",
        "",
        &O::burn_in,
        {},
        "Of those, not summarised",
        "",
        "whole number from 0 to ste.mh.iterations - 1"},
       {"ste.mh.proposal", "", &O::proposal, positive(1.0, "of each parameter's range"),
        "Proposal std per parameter, a share of its prior range", "the default is {default}"}}};
  return table;
}

void MhOptions::validate() const {
  plumekit::validate(mh_option_table(), *this);
  check_count("ste.mh.burn_in", burn_in, 0, iterations - 1LL,
              "it must be less than ste.mh.iterations; the default is " +
                  default_text(mh_option_table().entry("ste.mh.burn_in")));
}

const OptionTable<NavigationOptions>& navigation_option_table() {
  using O = NavigationOptions;
  static const OptionTable<O> table{
      "STE navigation (ste::NavigationOptions)",
      {{"ste.navigation.alpha", "--alpha", &O::alpha, non_negative(1.0, ""),
        "Weight of the KL move against the source move"},
       {"ste.navigation.beta", "--beta", &O::beta, non_negative(1.0, ""),
        "Weight of the posterior against the inverse distance"},
       {"ste.navigation.step", "--step", &O::step, positive(100.0, "m"),
        "Candidate lattice spacing, m"},
       {"ste.navigation.lattice", "--lattice", &O::lattice, count_range(1, 20),
        "Candidates up to this many steps per axis: (2 L + 1)^2 - 1 of them"},
       {"ste.navigation.reward",
        "--reward",
        enum_field(&O::reward, &to_string, &parse_reward, "kl, expected"),
        {},
        "Candidate score: kl (the thesis's, at the expected source) or expected (the expected "
        "information gain over the posterior's sources)"},
       {"ste.navigation.candidates",
        "--candidates",
        enum_field(&O::candidates, &to_string, &parse_candidates, "lattice, floor, auto"),
        {},
        "Where the robot may go next: lattice (moves around it, the thesis's), floor (also goals "
        "over the whole reachable floor, taken when one offers more than twice the moves' "
        "expected gain per second of travel and sampling), or auto (floor on arenas larger than "
        "the thesis's 10 x 4 m, lattice on the others)"},
       {"ste.navigation.floor_spacing", "--floor-spacing", &O::floor_spacing, positive(100.0, "m"),
        "Spacing of the floor's goals, m (--candidates floor)"},
       {"ste.navigation.floor_gain_cells", "", &O::floor_gain_cells, count_range(16, 1'000'000),
        "Floor: posterior cells drawn for each goal's expected gain"},
       {"ste.navigation.enhanced",
        "",
        &O::enhanced,
        {},
        "The thesis's combined target (section 13.2); false: the MAP"}}};
  return table;
}

void NavigationOptions::validate() const {
  plumekit::validate(navigation_option_table(), *this);
}

const OptionTable<StopOptions>& stop_option_table() {
  using O = StopOptions;
  const std::string thesis = std::to_string(O::kThesisMaxSamples);
  static const OptionTable<O> table{
      "STE stop rule (ste::StopOptions)",
      {{"ste.stop.max_samples", "--max-samples", &O::max_samples, count_range(0, 100'000),
        "Stop after this many samples (0: " + thesis +
            ", or on a floor of more than 500 m^2 one per 10 m^2 of its reachable free space)",
        "the default is {default} (auto: " + thesis + ", more on large floors)"},
       // 1 or more stops after the first sample (a test uses it).
       {"ste.stop.entropy_fraction", "--entropy-fraction", &O::entropy_fraction,
        non_negative(100.0, ""),
        "Stop when the posterior's entropy on the thesis's bins falls below this fraction of its "
        "maximum",
        "the default is {default}; 1 or more stops after the first sample"},
       {"ste.stop.seen_mass", "--seen-mass", &O::seen_mass, non_negative(1.0, ""),
        "Stop on entropy only with this share of the posterior on sources the samples could "
        "tell from no source (0: also declare sources whose plume reached no sample)",
        "the default is {default}; 0 declares unseen sources too"},
       {"ste.stop.confidence_radius", "--confidence-radius", &O::confidence_radius,
        non_negative(100.0, "m"),
        "Also stop once --confidence-mass of the posterior lies within this radius of the "
        "estimate, m (with --seen-mass as the entropy rule; 0: off, the thesis's rule alone)",
        "0 means off"},
       {"ste.stop.confidence_mass", "--confidence-mass", &O::confidence_mass,
        real_range(0.0, 1.0, "", true),
        "The share of the posterior --confidence-radius asks for"}}};
  return table;
}

void StopOptions::validate() const {
  plumekit::validate(stop_option_table(), *this);
}

const OptionTable<PhysicsPlumeOptions>& physics_option_table() {
  using O = PhysicsPlumeOptions;
  static const OptionTable<O> table{
      "STE physics plume model (ste::PhysicsPlumeOptions)",
      {{"ste.physics.source_cell", "", &O::source_cell, positive(10.0, "m"),
        "Candidate source cells, m"},
       {"ste.physics.scale_lo", "", &O::scale_lo, positive(1e6, ""),
        "Lower prior bound of the release scale (1: the dataset's release rate)",
        "1 is the dataset's release rate"},
       {"ste.physics.scale_hi",
        "",
        &O::scale_hi,
        {},
        "Upper prior bound of the release scale",
        "",
        "from ste.physics.scale_lo to 1e+06"}}};
  return table;
}

void PhysicsPlumeOptions::validate() const {
  const OptionTable<PhysicsPlumeOptions>& table = physics_option_table();
  validate_entry(table.entry("ste.physics.source_cell"), *this);
  advection_diffusion.validate();
  validate_entry(table.entry("ste.physics.scale_lo"), *this);
  check_range("ste.physics.scale_hi", scale_hi, scale_lo, 1e6, "",
              "it must be at least ste.physics.scale_lo");
}

const OptionTable<GaussianPlumeBounds>& gaussian_option_table() {
  using O = GaussianPlumeBounds;
  static const OptionTable<O> table{
      "STE Gaussian plume model's prior bounds (ste::GaussianPlumeBounds)",
      {{"ste.gaussian.q_max", "", &O::q_max, positive(1e12, ""), "Largest release Q"},
       {"ste.gaussian.a_min", "", &O::a_min, positive(10.0, ""),
        "Smallest sigma_y growth per metre downwind"},
       {"ste.gaussian.a_max",
        "",
        &O::a_max,
        {},
        "Largest sigma_y growth per metre downwind",
        "",
        "from ste.gaussian.a_min to 10"},
       {"ste.gaussian.b_min", "", &O::b_min, positive(100.0, "m"),
        "Smallest sigma_y at the source, m"},
       {"ste.gaussian.b_max",
        "",
        &O::b_max,
        {},
        "Largest sigma_y at the source, m",
        "",
        "from ste.gaussian.b_min to 100 m"}}};
  return table;
}

void GaussianPlumeBounds::validate() const {
  plumekit::validate(gaussian_option_table(), *this);
  check_range("ste.gaussian.a_max", a_max, a_min, 10.0, "", "it must be at least a_min");
  check_range("ste.gaussian.b_max", b_max, b_min, 100.0, "m", "it must be at least b_min");
}

}  // namespace plumekit::ste
