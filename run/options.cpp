// The range checks of the run loop's options: a scenario's (SteOptions, under "ste."), a team's
// and an evaluation's ("evaluation.").
#include <algorithm>
#include <cmath>
#include <filesystem>

#include "core/error.hpp"
#include "core/option_check.hpp"
#include "run/evaluation.hpp"
#include "run/option_tables.hpp"
#include "run/scenario.hpp"
#include "ste/surrogate_plume.hpp"

namespace plumekit::run {
const OptionTable<TeamOptions>& team_option_table() {
  using O = TeamOptions;
  static const OptionTable<O> table{
      "Team (run::TeamOptions)",
      {{"ste.team.robots", "--robots", &O::robots, count_range(1, 64),
        "Robots running STE together in one world (the thesis's teams: 1-3), started side by "
        "side --separation apart",
        "the thesis's teams have 1 to 3 robots"},
       {"ste.team.strategy",
        "--team",
        enum_field(&O::strategy, &to_string, &parse_team_strategy,
                   "individualist, cooperative, collaborative"),
        {},
        "The team's strategy: individualist (each alone; the first declaration ends the "
        "mission), cooperative (every sample shared), collaborative (shared samples, virtual "
        "samples at teammates' goals, task swaps)"},
       {"ste.team.separation", "--separation", &O::separation, non_negative(10.0, "m"),
        "No robot of a team moves closer than this to a teammate, m"},
       {"ste.team.patience_s", "", &O::patience_s, positive(3600.0, "s"),
        "A robot kept waiting this long on one way samples where it stands, s"}}};
  return table;
}

void TeamOptions::validate() const {
  plumekit::validate(team_option_table(), *this);
}

const OptionTable<EvaluationOptions>& evaluation_option_table() {
  using O = EvaluationOptions;
  static const OptionTable<O> table{
      "Evaluation (run::EvaluationOptions)",
      {{"evaluation.runs", "--runs", &O::runs, count_range(1, 1'000'000),
        "Runs per source, from seeded random free starts"},
       {"evaluation.seeds", "--seeds", &O::seeds, count_range(1, 1000),
        "Evaluate with seeds SEED, SEED + 1, ... this many, pooled (runs.csv then has a seed "
        "column)"},
       {"evaluation.threads", "--threads,-j", &O::threads, count_range(0, 1024),
        "Runs in parallel, and threads of each surrogate table build (0: one per core)",
        "0 means one per core"},
       {"evaluation.source_count", "--sources", &O::source_count, count_range(0, 1'000'000),
        "Only the first K sources of each map (0: all; a labelled subset)",
        "0 means all of each map's sources"}}};
  return table;
}

ste::LikelihoodOptions SteOptions::likelihood_options() const {
  ste::LikelihoodOptions l = default_likelihood(model);
  l.sigma_m = likelihood.sigma_m.value_or(l.sigma_m);
  l.sigma_d = likelihood.sigma_d;
  l.sigma_rel = likelihood.sigma_rel.value_or(l.sigma_rel);
  l.sigma_std = likelihood.sigma_std.value_or(l.sigma_std);
  return l;
}

double SteOptions::source_cell_in_use() const {
  switch (model) {
    case PlumeModelKind::Surrogate:
      return source_cell.value_or(ste::SurrogatePlumeOptions{}.source_cell);
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
  const std::vector<std::uint8_t> free = ste::free_cells(map, probe, 0.0);
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
  if (team.robots > 1 && !methods::find_method(method.name).traits.teams)
    throw OptionError("ste.team.robots", "teams run plumekit's STE (seed 004 ch. 13); the " +
                                             method.name + " method runs one robot");
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
  if (model == PlumeModelKind::Surrogate && uses_plume_model(method.name)) check_model_file();
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
                          " not found (train one, see docs/design/surrogate.md, or use "
                          "ste.model physics or gaussian)");
}

void EvaluationOptions::validate() const {
  plumekit::validate(evaluation_option_table(), *this);
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

}  // namespace plumekit::run
