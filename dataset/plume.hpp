#pragma once
// One map's plumes on the sensor grid, by either model: the dispatch the
// dataset generator and `plumekit plume` share. The advection-diffusion
// operator is factored once here, in the constructor, for all sources.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "cfd/advection_diffusion.hpp"
#include "cfd/options.hpp"
#include "cfd/wind_field.hpp"
#include "core/grid.hpp"
#include "map/map.hpp"
#include "surrogate/features.hpp"
#include "world/filament_model.hpp"
#include "world/gas_sensor.hpp"

namespace plumekit::dataset {

// How a dataset's plumes are simulated (`--plume-model` in `plume` and `dataset generate`).
enum class PlumeSimulator { Filament, AdvectionDiffusion };
const char* to_string(PlumeSimulator m);
// OptionError naming plume.model and the value.
PlumeSimulator parse_plume_simulator(const std::string& name);
// Every simulator by its name ("filament", "advection-diffusion").
std::vector<std::pair<std::string, PlumeSimulator>> plume_simulator_names();

struct PlumeOptions {
  PlumeSimulator model = PlumeSimulator::Filament;  // plume.model
  world::FilamentOptions filament;
  cfd::AdvectionDiffusionOptions advection_diffusion;
  // The static sensors' gas sensor (sensor.gas, sensor.baseline; issue 18):
  // the targets are then what that sensor reads (filament model; the
  // advection-diffusion plume is steady, so it only takes a baseline).
  world::GasSensorModel sensor;
  // Validates both models' options (the unused model's too: a dataset's
  // parameters.json records them all). OptionError naming the field.
  void validate() const;
  // plume.release_rate: both models release the same amount per second and metre of depth.
  void set_release_rate(double rate) {
    filament.release_rate = rate;
    advection_diffusion.release_rate = rate;
  }
};

// The advection-diffusion options whose steady plume is the filament world's long-time mean (up
// to its meander): the dataset's diffusivity and release rate, and the world's decay, 1 over a
// filament's lifetime (FilamentOptions::lifetime_s, 28 s): what ste's physics model predicts and
// what gas maps are scored against.
cfd::AdvectionDiffusionOptions filament_world_mean();

// A source must lie in the map's free space: OptionError naming plume.source otherwise.
void check_source(const Map& map, Vec2 source);

struct PlumeTargets {
  Grid<double> mean;
  Grid<double> std;  // all zero for advection-diffusion: its plume is the exact mean
  world::FilamentSummary filament;
};

class MapPlumes {
 public:
  // Validates the options first.
  MapPlumes(const Map& map, const cfd::WindField& wind, const GridShape& sensors,
            const PlumeOptions& options);
  ~MapPlumes();
  // Sensors inside obstacles read 0 in both models. `seed` drives the
  // filament model's random numbers and is ignored by advection-diffusion.
  PlumeTargets run(Vec2 source, std::uint64_t seed) const;

 private:
  const Map& map_;
  const cfd::WindField& wind_;
  GridShape sensors_;
  PlumeOptions options_;
  // Advection-diffusion only: the operator factored once, read at the sensors.
  std::unique_ptr<surrogate::PhysicsFeature> ad_;
};

// `plumekit plume`: one source's plume in a map whose wind is solved by the flow policy
// (cfd::solve_wind), or read from `wind_dir` (a `plumekit flow` output for this map,
// cfd/wind_file.hpp) when one is given, with the time each part took.
// With `series_s` > 0, also the filament plume as it moves (plume_series), for that many seconds.
struct SinglePlume {
  PlumeTargets targets;
  double flow_s = 0.0, plume_s = 0.0;
  struct Series {
    GridShape grid;
    double every_s = 1.0;
    std::vector<std::vector<float>> frames;  // frame k at k * every_s after the spin-up
  } series;
};
SinglePlume single_plume(const Map& map, Vec2 source, const PlumeOptions& options,
                         const cfd::FlowOptions& flow, std::uint64_t seed,
                         const std::filesystem::path& wind_dir = {}, double series_s = 0.0);

// The grid a plume over time is shown on (plume_series, a run's replay): cells of at least 0.1 m,
// at most about 10,000 of them (a grid a second costs the world's time; finer than a video's
// pixels shows no more).
GridShape plume_series_grid(const Map& map);

// The filament plume of `source` (seeded by `seed`) as it moves: spun up as the dataset's, then
// its concentration on `grid` (the sensors' line of sight to each filament) every `every_s` for
// `seconds`, frame 0 at the spin-up's end.
std::vector<std::vector<float>> plume_series(const Map& map, const cfd::WindField& wind,
                                             Vec2 source, const world::FilamentOptions& options,
                                             std::uint64_t seed, const GridShape& grid,
                                             double seconds, double every_s);

}  // namespace plumekit::dataset
