#pragma once
// Everything STE needs for one map, built once and shared (read-only, so
// thread-safe) by all runs on it: the wind, the plume model, the planner and
// its free space. A run adds its own estimator, world and start.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "cfd/options.hpp"
#include "cfd/wind_field.hpp"
#include "core/thread_pool.hpp"
#include "map/map.hpp"
#include "methods/method_options.hpp"
#include "methods/registry.hpp"
#include "planner/free_space.hpp"
#include "planner/planner.hpp"
#include "run/method_run.hpp"
#include "run/team.hpp"
#include "ste/forward_model.hpp"
#include "ste/gaussian_plume.hpp"
#include "ste/mh_estimator.hpp"
#include "ste/physics_plume.hpp"
#include "world/random_streams.hpp"
#include "world/simulated_world.hpp"

namespace plumekit::run {

class ReplayRecorder;  // run/replay_recorder.hpp

// The methods' options and the registry's lookups, as the run layer names them.
using methods::ends_on_arrival;
using methods::find_method;
using methods::make_method;
using methods::method_names;
using methods::MethodOptions;
using methods::parse_method_list;
using methods::stops_in_source_box;
using methods::uses_plume_model;

enum class PlumeModelKind { Surrogate, Gaussian, Physics };
const char* to_string(PlumeModelKind kind);
// "surrogate", "gaussian", "physics"; InputError naming the value otherwise.
PlumeModelKind parse_plume_model_kind(const std::string& name);

// How the robot samples and ends (--protocol; docs/design/ste.md, "Readings on the way"). moving,
// the default since issue 47: the gas sensor reads along every path too, a stop lasts only as long
// as its mean is unsettled (world.read_while_moving, world.adaptive_stop), STE may also declare by
// the confidence rule (stop.confidence_radius) and the robot then drives to its estimate
// (approach). thesis: the thesis's stop, sample 5 s, decide, move, read only while standing,
// declare by entropy and stay: every result made before issue 47.
enum class SamplingProtocol { Moving, Thesis };
const char* to_string(SamplingProtocol protocol);
// "moving", "thesis"; OptionError naming ste.protocol otherwise.
SamplingProtocol parse_sampling_protocol(const std::string& name);

// The sample error each model runs with unless told otherwise: the thesis's sigma_M = 30 for the
// Gaussian baseline. For the physics model, sigma_M = 150: a 5 s mean of the filament world
// scatters about its steady mean by about 100 near a plume's axis; chosen on held-out random maps
// in the faithful world (docs/design/ste.md). Plus 15 % of the prediction (sigma_rel): near a
// source the 5 s means scatter by thousands, and a fixed 150 let a few of them lock the posterior
// onto a cell next to the source's; chosen on held-out buildings (docs/validation.md, "Floors").
// For the surrogate, sigma_M = 200 (about the shipped model's RMSE on the test maps) plus twice the
// CNN's own predicted std of the readings (sigma_std), since a 5 s sample departs from the mean,
// and the CNN errs, most where the plume is intermittent; chosen on held-out random maps
// (docs/design/ste.md). With the moving protocol, the CNN's std once (sigma_std 1): short stops
// and readings on the way, chosen on the same held-out sets (results/ste-time, "The likelihood of
// the moving protocol").
ste::LikelihoodOptions default_likelihood(PlumeModelKind kind,
                                          SamplingProtocol protocol = SamplingProtocol::Moving);

// The world's options with `protocol`'s sampling: readings on the way and adaptive stops for
// moving, neither for thesis; the rest at their defaults.
world::WorldOptions protocol_world(SamplingProtocol protocol);
// The stop rule of `protocol`: the thesis's entropy rule, and for moving the confidence rule too
// (0.95 of the posterior within 0.3 m, chosen on held-out sets: results/ste-time).
ste::StopOptions protocol_stop(SamplingProtocol protocol);

// The likelihood's settings in SteOptions. sigma_m, sigma_rel and sigma_std follow the plume model
// unless set (default_likelihood): the same number cannot suit a CNN and an exact model.
struct SteLikelihood {
  std::optional<double> sigma_m;  // unset: 200 for the surrogate, 150 for physics, 30 for gaussian
  double sigma_d = 0.0;
  std::optional<double> sigma_rel;  // unset: 0.15 for physics, 0 otherwise
  // unset: for the surrogate 1 (moving protocol) or 2 (thesis), 0 otherwise (surrogate only)
  std::optional<double> sigma_std;
};

// Every option of a localization, with its default (docs/methods.md, "Options"). The default plume
// model is the surrogate; its CNN file (model_path) has no default here, since where the shipped
// model lies is the CLI's to say (it fills in data/models/plume-unet.pkcnn).
struct SteOptions {
  // The localization method (--method): plumekit's STE, or one of the seeds' trackers and
  // particle filters, which use no plume model (the model's options below are then unused).
  MethodOptions method;
  // How the robot samples (--protocol); set it with set_protocol, which sets the world's half too.
  // The surrogate's unset sigma_std follows it (default_likelihood).
  SamplingProtocol protocol = SamplingProtocol::Moving;
  PlumeModelKind model = PlumeModelKind::Surrogate;
  std::string model_path;  // the surrogate's CNN file (plumekit-cnn)
  SteLikelihood likelihood;
  ste::BinOptions bins;
  ste::MhOptions mh;
  ste::NavigationOptions navigation;
  ste::StopOptions stop = protocol_stop(protocol);
  world::WorldOptions world = protocol_world(protocol);
  // A team of robots instead of one (--robots, --team; run/team.hpp).
  TeamOptions team;
  // The wind every run of a map shares (the flow's defaults: 5 cm cells).
  cfd::FlowOptions flow;
  // A `plumekit flow` output folder for this map (either engine) whose wind is
  // used instead of solving one (cfd/wind_file.hpp); empty: solve it.
  std::string wind_dir;
  // The diffusivity of the physics model, and the release-scale prior [scale_lo, scale_hi] of
  // the surrogate and physics models. Its source_cell is the physics default of `source_cell`.
  ste::PhysicsPlumeOptions physics;
  ste::GaussianPlumeBounds gaussian;
  // Candidate source grid, m, of the surrogate and physics models; unset: the model's own default
  // (SurrogatePlumeOptions: 0.2 m; physics.source_cell: 0.1 m). The Gaussian plume has none.
  std::optional<double> source_cell;
  // The surrogate's table grid, m (one network run per allowed cell); unset: source_cell, or
  // coarser on maps of over 100 m^2 of free space (surrogate_table_cell). At least source_cell.
  std::optional<double> table_cell;
  double margin = 0.15;             // m, the planner's clearance (thesis 14.3.1)
  std::string table_cache;          // folder caching surrogate tables; empty: none
  int threads = kDefaultThreads;    // for the surrogate's table build; 0: one per core
  double min_start_distance = 1.0;  // m, random starts are at least this far from the source
  // m: a run ends as soon as the robot comes this close to the source, on its way too (seed 004
  // ch. 15's benchmark protocol: 0.5 m; SourceDisc). 0: never, but levy-taxis always ends at 0.5 m.
  double success_radius = 0.0;
  // s: STE's stretches of readings taken on the way (world.read_while_moving; passing_options).
  double passing_window_s = 1.0;
  // With readings on the way, the floor's goals are scored with the gains along their paths
  // (ste::MissionPace::passing_weight_per_m).
  bool path_scoring = false;
  // After it stops, a robot alone drives to its estimate and the mission ends there
  // (MethodRunOptions::approach). A team does not (its robots stop where they declare).
  bool approach = protocol == SamplingProtocol::Moving;

  // The likelihood the plume model runs with (the unset sigmas filled in).
  ste::LikelihoodOptions likelihood_options() const;
  // How STE takes the readings on the way: the window, and from the world the reading interval,
  // the stop's length and the gas sensor's mean delay.
  ste::PassingOptions passing_options() const;
  // What a move costs and reads, for the navigator: the world's speed and stop, and with
  // readings on the way and path_scoring the share of a stop each metre reads.
  ste::MissionPace mission_pace() const;
  // Whether the run reads the CNN file `model_path`: a method with a plume model, the surrogate.
  bool uses_cnn() const;
  // The candidate source grid in use (0 for the Gaussian plume, which has none).
  double source_cell_in_use() const;
  // The surrogate's table grid in use on `map` (0 for the other models).
  double table_cell_in_use(const Map& map) const;
  // Every field, the nested options' too (OptionError naming it: "ste.world.noise", ...), and
  // that a surrogate's model file exists. Scenario's constructor calls it.
  void validate() const;

 private:
  void check_model_file() const;
};

// Applies the preset `protocol` (--protocol): the field, the world's read_while_moving and
// adaptive_stop, the stop rule's confidence_radius and confidence_mass, and approach. Flags given
// with it override their part of it (the CLI and Python apply it first).
void set_protocol(SteOptions& options, SamplingProtocol protocol);

// The surrogate's default table cell on `map` for candidates of `source_cell`: the source cell
// itself, or on maps with over kSurrogateTableArea of free space the cell (rounded up to 5 cm,
// at least source_cell) that gives about kSurrogateTableCells free cells, so that the table (one
// plume per cell) stays within a minute to build and its memory bounded (docs/validation.md, "The
// learned model at building scale").
inline constexpr double kSurrogateTableArea = 100.0;  // m^2
inline constexpr double kSurrogateTableCells = 2500;
double surrogate_table_cell(const Map& map, double source_cell);

// What a run is labelled with in reports and pictures: STE's plume model ("surrogate", ...), or
// the method's name ("surge-cast", ...).
std::string run_label(const SteOptions& options);

class Scenario {
 public:
  // Solves the wind (options.flow; upwind if Newton stalls with central convection) and builds
  // the plume model. InputError for a map STE cannot run on.
  Scenario(const Map& map, const SteOptions& options);
  // The same with the wind of `same_map`, a scenario of this map with the same flow options (the
  // other methods of `evaluate --method a,b,...`): no second solve.
  Scenario(const Map& map, const SteOptions& options, const Scenario& same_map);
  ~Scenario();

  const Map& map() const { return map_; }
  const SteOptions& options() const { return options_; }
  const cfd::WindField& wind() const { return wind_; }
  // The plume model; STE's alone (has_model() is false for the other methods).
  bool has_model() const { return model_ != nullptr; }
  const ste::ForwardModel& model() const;
  const planner::FreeSpace& free_space() const { return *space_; }
  double wind_s() const { return wind_s_; }
  // The plume model's build: the surrogate's table, and the readings at the floor's goals.
  double model_build_s() const { return model_build_s_; }
  bool table_from_cache() const { return table_from_cache_; }
  // The surrogate's table grid in use, m (SteOptions::table_cell_in_use); 0 for the other models.
  double table_cell() const { return table_cell_; }

  // Checks a true source and a start (OptionError on ste.source / ste.start naming the fault);
  // a start inside the planner's margin is moved to the nearest free point (the caller reports
  // the move: the point returned differs from the one given).
  Vec2 check_source(Vec2 source) const;
  Vec2 check_start(Vec2 start) const;
  // A uniformly random start in the free space that can reach the source,
  // at least min_start_distance from it.
  Vec2 random_start(Vec2 source, std::uint64_t seed) const;
  // The start of run `run` of a source: the map's own starts (Map::starts) in turn, skipping
  // those closer than min_start_distance to the source or that cannot reach it; a map without
  // starts gives random_start(source, seed). InputError when no start of the map qualifies.
  Vec2 run_start(Vec2 source, int run, std::uint64_t seed) const;

  // A fresh estimator on this scenario's plume model (the grid estimator on a source table, MH
  // otherwise); `seed` drives MH.
  std::unique_ptr<ste::Estimator> make_estimator(std::uint64_t seed) const;
  const planner::Planner& planner() const { return *planner_; }
  const ste::Navigator& navigator() const { return *navigator_; }

  // One localization run with the options' method (a team's when options.team.robots > 1, its
  // first robot at `start`: team_starts); `seed` drives the plume, the sensor noise, MH and the
  // particle filter. A `recorder` records the run's replay (run/replay_recorder.hpp).
  LocalizationResult run(Vec2 source, Vec2 start, std::uint64_t seed,
                         ReplayRecorder* recorder = nullptr) const;
  // The same run in `world`, which holds the plume of `source` and `seed` (a robot of a shared
  // plume: world/shared_plume.hpp).
  LocalizationResult run(world::SimulatedWorld& world, Vec2 start, std::uint64_t seed,
                         ReplayRecorder* recorder = nullptr) const;

  // The starts of a team whose first robot starts at `first`: the team is deployed together, its
  // other robots on the free points nearest `first` of a lattice of the team's separation
  // (nearest first, then counter-clockwise from downwind x), in the piece of free space that
  // reaches `source`. InputError when the piece has no room for them.
  std::vector<Vec2> team_starts(Vec2 first, Vec2 source) const;
  // A team's run (options.team.robots robots) from `starts`; `seed` drives the plume, each
  // robot's sensors and MH (team_robot_seed).
  LocalizationResult run_team(Vec2 source, const std::vector<Vec2>& starts, std::uint64_t seed,
                              ReplayRecorder* recorder = nullptr) const;

  // The shortest collision-free way from `start` to `source` at the planner's margin (a source
  // inside the margin is reached at the free point nearest it, then straight), m; NaN when the
  // source cannot be reached.
  double optimum_path_m(Vec2 start, Vec2 source) const;

  // The plume trackers' success box of a source: along the steady wind at the source.
  SourceBox source_box(Vec2 source) const;

  // The steady advection-diffusion mean of a source on the flow grid: the
  // picture's background (the filament plume's long-time mean, up to its meander).
  Grid<double> mean_plume(Vec2 source) const;

 private:
  // The piece of free space (at the planner's margin) that `p`, or the free point nearest it,
  // lies in: a start must be in its source's.
  int region_reaching(Vec2 p) const;
  // How STE takes the readings on the way, when the robot reads while moving; else null.
  const ste::PassingOptions* passing() const {
    return options_.world.read_while_moving ? &passing_ : nullptr;
  }
  // Fills r.times (run/mission_times.hpp) for a run to `source`.
  void add_mission_times(LocalizationResult& r, Vec2 source) const;
  // run(world, ...) without its times.
  LocalizationResult run_in(world::SimulatedWorld& world, Vec2 start, std::uint64_t seed,
                            ReplayRecorder* recorder) const;

  // The wind of `same_map`, or solved when it is null.
  Scenario(const Map& map, const SteOptions& options, const Scenario* same_map);

  Map map_;
  SteOptions options_;
  ste::PassingOptions passing_;  // options_.passing_options()
  cfd::WindField wind_;
  std::unique_ptr<ste::ForwardModel> model_;
  std::unique_ptr<planner::Planner> planner_;
  std::unique_ptr<planner::FreeSpace> space_;
  std::unique_ptr<ste::Navigator> navigator_;
  GridShape bins_;
  double wind_s_ = 0.0, model_build_s_ = 0.0;
  bool table_from_cache_ = false;
  double table_cell_ = 0.0;
};

}  // namespace plumekit::run
