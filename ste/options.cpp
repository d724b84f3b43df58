// The range checks of STE's options structs (ste/README.md, "Options"). Field
// names are the options' dotted paths under "ste."; the filament plume of the
// simulated world and the physics model's advection-diffusion check their own
// fields ("plume.*", dataset/).
#include <algorithm>
#include <cmath>
#include <filesystem>

#include "core/error.hpp"
#include "core/option_check.hpp"
#include "ste/evaluation.hpp"
#include "ste/scenario.hpp"
#include "ste/surrogate_plume.hpp"

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

void TeamOptions::validate() const {
  check_count("ste.team.robots", robots, 1, 64, "the thesis's teams have 1 to 3 robots");
  check_non_negative("ste.team.separation", separation, 10.0, "m", "the default is 0.3 m");
  check_positive("ste.team.patience_s", patience_s, 3600.0, "s", "the default is 10 s");
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

void WorldOptions::validate() const {
  filament.validate();
  check_positive("ste.world.speed", speed, 100.0, "m/s", "the default is 0.5 m/s");
  check_positive("ste.world.sample_s", sample_s, 3600.0, "s", "the thesis uses 5 s");
  check_positive("ste.world.sample_rate", sample_rate, 1000.0, "Hz", "the thesis uses 10 Hz");
  check_non_negative("ste.world.noise", noise, 1e9, "concentration units",
                     "0 means a noise-free sensor");
  sensor.validate();
  check_non_negative("ste.world.wind_direction_noise", wind_direction_noise_deg, 360.0, "degrees",
                     "0 is an exact anemometer; seed 000 measured 14-29 degrees");
  check_non_negative("ste.world.wind_variance_noise", wind_variance_noise_deg, 360.0, "degrees",
                     "0 takes the circular variance from the world's own wind; seed 002 used "
                     "23.08");
  check_non_negative("ste.world.position_noise", position_noise, 100.0, "m",
                     "0 is an exact position; seed 000's GPS (Eq. 4.3) is 1.08 m");
  check_non_negative("ste.world.odometry_drift", odometry_drift, 1.0, "m per sqrt(m)",
                     "0 records the true position");
  check_non_negative("ste.world.rotor_disc", rotor_disc, 10.0, "m",
                     "0 reads at a point; seed 000's rotor disturbance is 0.5 m");
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

LikelihoodOptions SteOptions::likelihood_options() const {
  LikelihoodOptions l = default_likelihood(model);
  l.sigma_m = likelihood.sigma_m.value_or(l.sigma_m);
  l.sigma_d = likelihood.sigma_d;
  l.sigma_rel = likelihood.sigma_rel.value_or(l.sigma_rel);
  l.sigma_std = likelihood.sigma_std.value_or(l.sigma_std);
  return l;
}

double SteOptions::source_cell_in_use() const {
  switch (model) {
    case PlumeModelKind::Surrogate:
      return source_cell.value_or(SurrogatePlumeOptions{}.source_cell);
    case PlumeModelKind::Physics:
      return source_cell.value_or(physics.source_cell);
    case PlumeModelKind::Gaussian:
      break;
  }
  return 0.0;
}

double surrogate_table_cell(const Map& map, double source_cell) {
  if (map.width * map.height <= kSurrogateTableArea) return source_cell;  // small: no free count
  const GridShape probe = GridShape::with_cell(map.width, map.height, 0.2);
  const std::vector<std::uint8_t> free = free_cells(map, probe, 0.0);
  const double area = static_cast<double>(std::count(free.begin(), free.end(), std::uint8_t{1})) *
                      probe.dx() * probe.dy();
  if (area <= kSurrogateTableArea) return source_cell;
  const double cell = std::sqrt(area / kSurrogateTableCells);
  return std::max(source_cell, std::ceil(cell / 0.05 - 1e-9) * 0.05);
}

double SteOptions::table_cell_in_use(const Map& map) const {
  if (model != PlumeModelKind::Surrogate) return 0.0;
  const double cell = source_cell_in_use();
  return table_cell ? std::max(cell, *table_cell) : surrogate_table_cell(map, cell);
}

void SteOptions::validate() const {
  method.validate();
  likelihood_options().validate();
  if (likelihood.sigma_std && *likelihood.sigma_std != 0.0 && model != PlumeModelKind::Surrogate)
    throw OptionError("ste.likelihood.sigma_std",
                      "only the surrogate predicts the std of the readings; leave it unset for "
                      "the " +
                          std::string(to_string(model)) + " plume model");
  bins.validate();
  mh.validate();
  navigation.validate();
  stop.validate();
  world.validate();
  team.validate();
  if (team.robots > 1 && world.odometry_drift > 0.0)
    throw OptionError("ste.team.robots",
                      "teams run in the global framework (a map and positions): no odometry drift");
  if (team.robots > 1 && method.kind != MethodKind::Ste)
    throw OptionError("ste.team.robots", "teams run plumekit's STE (seed 004 ch. 13); the " +
                                             std::string(to_string(method.kind)) +
                                             " method runs one robot");
  flow.validate();
  physics.validate();
  gaussian.validate();
  if (source_cell) {
    if (model == PlumeModelKind::Gaussian)
      throw OptionError("ste.source_cell",
                        "only the surrogate and physics models have a source grid (the Gaussian "
                        "plume's MH runs on the bins); leave it unset");
    check_positive("ste.source_cell", *source_cell, 10.0, "m",
                   "the defaults are 0.2 m (surrogate) and 0.1 m (physics)");
  }
  if (table_cell) {
    if (model != PlumeModelKind::Surrogate)
      throw OptionError("ste.table_cell", "only the surrogate has a table; leave it unset");
    check_range("ste.table_cell", *table_cell, source_cell_in_use(), 10.0, "m",
                "it must be at least the source cell (" + compact(source_cell_in_use()) + " m)");
  }
  check_non_negative("ste.margin", margin, 10.0, "m", "the thesis's clearance is 0.15 m");
  check_count("ste.threads", threads, 0, 1024, "0 means one per core");
  check_non_negative("ste.min_start_distance", min_start_distance, 1000.0, "m",
                     "the default is 1 m");
  check_non_negative("ste.success_radius", success_radius, 100.0, "m",
                     "0 ends no run on arrival; seed 004 ch. 15 uses 0.5 m");
  if (model == PlumeModelKind::Surrogate && uses_plume_model(method.kind)) check_model_file();
}

void SteOptions::check_model_file() const {
  if (model_path.empty())
    throw OptionError("ste.model_path",
                      "the surrogate plume model needs a CNN model file; name one, or use "
                      "ste.model physics or gaussian");
  std::error_code ec;
  if (!std::filesystem::is_regular_file(model_path, ec))
    throw OptionError("ste.model_path",
                      model_path +
                          " not found (train one, see surrogate/README.md, or use "
                          "ste.model physics or gaussian)");
}

void EvaluationOptions::validate() const {
  check_count("evaluation.runs", runs, 1, 1'000'000, "the default is 3");
  check_count("evaluation.seeds", seeds, 1, 1000, "the default is 1");
  check_count("evaluation.threads", threads, 0, 1024, "0 means one per core");
  check_count("evaluation.source_count", source_count, 0, 1'000'000,
              "0 means all of each map's sources");
  if (part_n < 1 || part_k < 0 || part_k >= part_n)
    throw OptionError("evaluation.shard", "expected K/N with 0 <= K < N, got " +
                                              std::to_string(part_k) + "/" +
                                              std::to_string(part_n));
  ste.validate();
}

void EvaluationOptions::set_part(const std::string& k_of_n) {
  const PartOfN part = parse_part("evaluation.shard", k_of_n);
  part_k = part.k;
  part_n = part.n;
}

}  // namespace plumekit::ste
