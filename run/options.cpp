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

namespace {

// "200 for the surrogate, 150 for physics, 30 for gaussian": what an unset likelihood field
// is with each plume model (default_likelihood), and with the thesis's protocol where it differs.
std::string per_model(double ste::LikelihoodOptions::*field) {
  std::string text;
  for (PlumeModelKind kind :
       {PlumeModelKind::Surrogate, PlumeModelKind::Physics, PlumeModelKind::Gaussian}) {
    const double moving = default_likelihood(kind).*field,
                 thesis = default_likelihood(kind, SamplingProtocol::Thesis).*field;
    text += (text.empty() ? "" : ", ") + option_number(moving) + " for " +
            (kind == PlumeModelKind::Surrogate ? "the surrogate" : to_string(kind));
    if (thesis != moving) text += " (" + option_number(thesis) + " with --protocol thesis)";
  }
  return text;
}

}  // namespace

const OptionTable<SteLikelihood>& ste_likelihood_option_table() {
  using O = SteLikelihood;
  using L = ste::LikelihoodOptions;
  static const OptionTable<O> table{
      "Localization likelihood (run::SteLikelihood; ste::LikelihoodOptions with the plume "
      "model's defaults)",
      {{"ste.likelihood.sigma_m", "--sigma-m",
        optional_field(&O::sigma_m, [] { return per_model(&L::sigma_m); }),
        non_negative(1e9, "concentration units"),
        "Model error sigma_M, concentration units (the surrogate's: about the shipped model's "
        "RMSE on the test maps; physics: chosen on held-out maps; gaussian: the thesis's; pass "
        "30 for the thesis's physics)",
        "the thesis uses 30"},
       {"ste.likelihood.sigma_d", "--sigma-d", &O::sigma_d,
        non_negative(1e9, "concentration units"), "Measurement error sigma_D, concentration units",
        "0 in simulation, 125 in the thesis's wind tunnel"},
       {"ste.likelihood.sigma_rel", "--sigma-rel",
        optional_field(&O::sigma_rel, [] { return per_model(&L::sigma_rel); }),
        non_negative(100.0, ""),
        "Model error relative to the predicted concentration, added in quadrature to sigma_M "
        "(physics: chosen on held-out buildings)",
        "0 means none"},
       {"ste.likelihood.sigma_std", "--sigma-std",
        optional_field(&O::sigma_std, [] { return per_model(&L::sigma_std); }),
        non_negative(100.0, ""),
        "Model error in units of the surrogate's predicted std of the readings, added in "
        "quadrature (the surrogate only: the other models predict no std)",
        "0 means none"}}};
  return table;
}

constexpr const char* kPassingWindowHelp =
    "STE averages readings on the way over stretches this long, s (ste/passing_readings.hpp)";
constexpr const char* kPathScoringHelp =
    "With --read-while-moving, STE scores the floor's goals with the gains along their paths";
constexpr const char* kApproachHelp =
    "After it stops, the robot (alone, not a team) drives to its estimate and the mission ends "
    "when it arrives (GSL-Bench scores where the robot is)";
constexpr const char* kCnnHelp =
    "CNN model of the surrogate plume model: a plumekit-cnn file, or a shipped model's name "
    "(docs/data.md): hybrid (the default; any map), thesis (the thesis's 64 x 64; 10 x 4 m "
    "maps), v2, faithful (empty: hybrid; the CLI and Python find them)";

constexpr const char* kProtocolHelp =
    "How the robot samples and ends: moving (the sensor reads along every path too, a stop "
    "lasts --stop-min-s to --stop-s until its mean is settled, STE also declares by the "
    "confidence rule, and the robot then drives to its estimate: --read-while-moving true "
    "--adaptive-stops true --confidence-radius 0.3 --confidence-mass 0.95 --approach true) or "
    "thesis (stop, sample --stop-s, decide, move; declare by entropy and stay: false, false, 0, "
    "false; every result made before issue 47). Each of those flags overrides its part "
    "(docs/design/ste.md, \"Readings on the way\")";

namespace {

// --protocol: a preset, so setting it sets the world's halves too (set_protocol).
OptionEntry<SteOptions> protocol_entry() {
  using O = SteOptions;
  return {"ste.protocol",
          "--protocol",
          EnumField<O>{
              [](const O& o) { return std::string(to_string(o.protocol)); },
              [](O& o, const std::string& name) { set_protocol(o, parse_sampling_protocol(name)); },
              "moving, thesis"},
          {},
          kProtocolHelp};
}

}  // namespace

const OptionTable<SteOptions>& ste_option_table() {
  using O = SteOptions;
  static const OptionTable<O> table{
      "Localization (run::SteOptions)",
      {protocol_entry(),
       {"ste.model",
        "--plume-model",
        enum_field(&O::model, &to_string, &parse_plume_model_kind, "surrogate, gaussian, physics"),
        {},
        "STE's plume model: surrogate (the CNN), gaussian or physics"},
       {"ste.model_path", "--cnn", &O::model_path, {}, kCnnHelp},
       {"ste.source_cell", "--source-cell",
        optional_field(&O::source_cell,
                       [] {
                         return option_number(ste::SurrogatePlumeOptions{}.source_cell) +
                                " for the surrogate, " +
                                option_number(ste::PhysicsPlumeOptions{}.source_cell) +
                                " for physics";
                       }),
        positive(10.0, "m"),
        "Candidate source grid, m (surrogate and physics; the Gaussian plume has none)",
        "unset, it is {default}"},
       {"ste.table_cell",
        "--table-cell",
        optional_field(&O::table_cell,
                       [] {
                         return "the source cell, coarser on maps of over " +
                                option_number(kSurrogateTableArea) + " m^2 free: about " +
                                option_number(kSurrogateTableCells) + " cells";
                       }),
        {},
        "The surrogate's table grid, m: one network run per free cell, each candidate source "
        "reads the cells around it",
        "",
        "at least the source cell, at most 10 m"},
       {"ste.margin", "--margin", &O::margin, non_negative(10.0, "m"),
        "Planner clearance from obstacles, m", "the thesis's clearance is {default} m"},
       {"ste.table_cache",
        "--table-cache",
        &O::table_cache,
        {},
        "Folder caching surrogate tables (keyed by map and model hashes; empty: none)"},
       {"ste.threads", "", &O::threads, count_range(0, 1024),
        "Threads of the surrogate's table build (0: one per core; the commands' --threads)",
        "0 means one per core"},
       {"ste.min_start_distance", "", &O::min_start_distance, non_negative(1000.0, "m"),
        "Random starts are at least this far from the source, m"},
       {"ste.success_radius", "--success-radius", &O::success_radius, non_negative(100.0, "m"),
        "End a run as soon as the robot comes this close to the source, on its way too, m "
        "(seed 004 ch. 15's benchmark: 0.5; 0: never, but levy-taxis ends at 0.5)",
        "0 ends no run on arrival; seed 004 ch. 15 uses 0.5 m"},
       {"ste.passing_window_s", "--passing-window", &O::passing_window_s,
        real_range(0.0, 60.0, "s", true), kPassingWindowHelp},
       {"ste.path_scoring", "--path-scoring", &O::path_scoring, {}, kPathScoringHelp},
       {"ste.approach", "--approach", &O::approach, {}, kApproachHelp}}};
  return table;
}

ste::MissionPace SteOptions::mission_pace() const {
  ste::MissionPace pace{world.speed, world.sample_s};
  if (world.read_while_moving && path_scoring)
    pace.passing_weight_per_m = 1.0 / (world.speed * world.sample_s);
  return pace;
}

ste::PassingOptions SteOptions::passing_options() const {
  ste::PassingOptions p;
  p.window_s = passing_window_s;
  p.reading_s = 1.0 / world.sample_rate;
  p.stop_s = world.sample_s;
  p.lag_s = world.sensor.mean_delay_s();
  return p;
}

ste::LikelihoodOptions SteOptions::likelihood_options() const {
  ste::LikelihoodOptions l = default_likelihood(model, protocol);
  l.sigma_m = likelihood.sigma_m.value_or(l.sigma_m);
  l.sigma_d = likelihood.sigma_d;
  l.sigma_rel = likelihood.sigma_rel.value_or(l.sigma_rel);
  l.sigma_std = likelihood.sigma_std.value_or(l.sigma_std);
  return l;
}

bool SteOptions::uses_cnn() const {
  return model == PlumeModelKind::Surrogate && uses_plume_model(method.name);
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
  plumekit::validate(ste_likelihood_option_table(), likelihood);
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
  if (source_cell && model == PlumeModelKind::Gaussian)
    throw OptionError("ste.source_cell",
                      "only the surrogate and physics models have a source grid (the Gaussian "
                      "plume's MH runs on the bins); leave it unset");
  if (table_cell && model != PlumeModelKind::Surrogate)
    throw OptionError("ste.table_cell", "only the surrogate has a table; leave it unset");
  plumekit::validate(ste_option_table(), *this);
  if (table_cell)
    check_range("ste.table_cell", *table_cell, source_cell_in_use(), 10.0, "m",
                "it must be at least the source cell (" + compact(source_cell_in_use()) + " m)");
  if (uses_cnn()) check_model_file();
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
