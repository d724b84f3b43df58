#pragma once
// Everything STE needs for one map, built once and shared (read-only, so
// thread-safe) by all runs on it: the wind, the plume model, the planner and
// its free space. A run adds its own estimator, world and start.
#include <cstdint>
#include <memory>
#include <string>

#include "cfd/wind_field.hpp"
#include "core/map.hpp"
#include "planner/free_space.hpp"
#include "planner/planner.hpp"
#include "ste/gaussian_plume.hpp"
#include "ste/localizer.hpp"
#include "ste/mh_estimator.hpp"
#include "ste/physics_plume.hpp"
#include "ste/plume_model.hpp"
#include "ste/world.hpp"

namespace plumekit::ste {

enum class PlumeModelKind { Surrogate, Gaussian, Physics };
const char* to_string(PlumeModelKind kind);
// "surrogate", "gaussian", "physics"; InputError naming the value otherwise.
PlumeModelKind parse_plume_model_kind(const std::string& name);

// The sample error each model runs with unless told otherwise: the thesis's sigma_M = 30 for the
// Gaussian and physics models. For the surrogate, sigma_M = 200 (about the shipped model's RMSE on
// the test maps) plus twice the CNN's own predicted std of the readings (sigma_std), since a 5 s
// sample departs from the mean, and the CNN errs, most where the plume is intermittent; chosen on
// held-out random maps (ste/README.md).
LikelihoodOptions default_likelihood(PlumeModelKind kind);

struct SteOptions {
  PlumeModelKind model = PlumeModelKind::Physics;
  LikelihoodOptions likelihood;
  BinOptions bins;
  MhOptions mh;
  NavigationOptions navigation;
  StopOptions stop;
  WorldOptions world;
  // Also holds the release-scale prior [scale_lo, scale_hi] of the surrogate.
  PhysicsPlumeOptions physics;
  GaussianPlumeBounds gaussian;
  double margin = 0.15;  // m, the planner's clearance (thesis 14.3.1)
  // Surrogate: the model file, the candidate source cell (m), an optional
  // table cache directory, threads for the table build.
  std::string model_path;
  double surrogate_cell = 0.2;
  std::string table_cache;
  int table_threads = 2;
  double min_start_distance = 1.0;  // m, random starts are at least this far from the source
  // Every field, the nested options' too (OptionError naming it: "ste.world.noise", ...).
  // Scenario's constructor calls it.
  void validate() const;
};

class Scenario {
 public:
  // Solves the wind (central convection, upwind if Newton stalls) and builds
  // the plume model. InputError for a map STE cannot run on.
  Scenario(const Map& map, const SteOptions& options);
  ~Scenario();

  const Map& map() const { return map_; }
  const SteOptions& options() const { return options_; }
  const cfd::WindField& wind() const { return wind_; }
  const PlumeModel& model() const { return *model_; }
  const planner::FreeSpace& free_space() const { return *space_; }
  double wind_seconds() const { return wind_seconds_; }
  double model_seconds() const { return model_seconds_; }  // plume model / table build
  bool table_from_cache() const { return table_from_cache_; }

  // Checks a true source and a start (InputError naming the flag and the
  // fault); a start inside the planner's margin is moved to the nearest free point.
  Vec2 check_source(Vec2 source) const;
  Vec2 check_start(Vec2 start) const;
  // A uniformly random start in the free space that can reach the source,
  // at least min_start_distance from it.
  Vec2 random_start(Vec2 source, std::uint64_t seed) const;

  // One localization run; `seed` drives the plume, the sensor noise and MH.
  LocalizationResult run(Vec2 source, Vec2 start, std::uint64_t seed) const;

  // The steady advection-diffusion mean of a source on the flow grid: the
  // picture's background (the filament plume's long-time mean, up to its meander).
  Grid<double> mean_plume(Vec2 source) const;

 private:
  Map map_;
  SteOptions options_;
  cfd::WindField wind_;
  std::unique_ptr<PlumeModel> model_;
  std::unique_ptr<planner::Planner> planner_;
  std::unique_ptr<planner::FreeSpace> space_;
  std::unique_ptr<Navigator> navigator_;
  GridShape bins_;
  double wind_seconds_ = 0.0, model_seconds_ = 0.0;
  bool table_from_cache_ = false;
};

// Counter-based seeds: one stream per (seed, map, source, run).
std::uint64_t run_seed(std::uint64_t seed, std::uint64_t map, std::uint64_t source,
                       std::uint64_t run);

}  // namespace plumekit::ste
