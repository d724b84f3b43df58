#include "dataset/plume.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "cfd/flow_policy.hpp"
#include "cfd/wind_file.hpp"
#include "core/error.hpp"
#include "surrogate/features.hpp"

namespace plumekit::dataset {

const char* to_string(PlumeSimulator m) {
  return m == PlumeSimulator::Filament ? "filament" : "advection-diffusion";
}

PlumeSimulator parse_plume_simulator(const std::string& name) {
  if (name == "filament") return PlumeSimulator::Filament;
  if (name == "advection-diffusion") return PlumeSimulator::AdvectionDiffusion;
  throw OptionError("plume.model",
                    "unknown plume model '" + name + "'; use filament or advection-diffusion");
}

std::vector<std::pair<std::string, PlumeSimulator>> plume_simulator_names() {
  return {{"filament", PlumeSimulator::Filament},
          {"advection-diffusion", PlumeSimulator::AdvectionDiffusion}};
}

void PlumeOptions::validate() const {
  filament.validate();
  advection_diffusion.validate();
  sensor.validate();
  if (model == PlumeSimulator::AdvectionDiffusion && !sensor.ideal())
    throw OptionError("sensor.gas", "the " + sensor.name +
                                        " sensor needs the filament model: a sensor's response "
                                        "follows a time series, and advection-diffusion gives "
                                        "the steady mean only (use --simulator filament)");
}

void check_source(const Map& map, Vec2 source) {
  if (!map.is_free(source))
    throw OptionError("plume.source", to_string(map.to_frame(source)) +
                                          " is outside the arena or inside an obstacle");
}

MapPlumes::MapPlumes(const Map& map, const cfd::WindField& wind, const GridShape& sensors,
                     const PlumeOptions& options)
    : map_(map), wind_(wind), sensors_(sensors), options_(options) {
  options.validate();
  if (options.model == PlumeSimulator::AdvectionDiffusion)
    ad_ = std::make_unique<surrogate::PhysicsFeature>(map, wind, sensors_,
                                                      options.advection_diffusion);
}

MapPlumes::~MapPlumes() = default;

PlumeTargets MapPlumes::run(Vec2 source, std::uint64_t seed) const {
  check_source(map_, source);
  PlumeTargets t;
  if (ad_) {
    t.mean = (*ad_)(source);
    t.std = Grid<double>(sensors_, 0.0);
    for (std::size_t k = 0; k < sensors_.size(); ++k)
      if (!ad_->in_obstacle(k)) t.mean.values[k] += options_.sensor.baseline;
    return t;
  }
  world::SensorRecord r = world::simulate_filaments(map_, wind_, source, sensors_,
                                                    options_.filament, seed, options_.sensor);
  t.mean = std::move(r.mean);
  t.std = std::move(r.std);
  t.filament = r.summary;
  return t;
}

cfd::AdvectionDiffusionOptions filament_world_mean() {
  cfd::AdvectionDiffusionOptions o;
  o.decay_rate = 1.0 / world::FilamentOptions{}.lifetime_s();
  return o;
}

GridShape plume_series_grid(const Map& map) {
  const double cell = std::max(0.1, std::sqrt(map.width * map.height / 10000.0));
  return GridShape::with_cell(map.width, map.height, cell);
}

std::vector<std::vector<float>> plume_series(const Map& map, const cfd::WindField& wind,
                                             Vec2 source, const world::FilamentOptions& options,
                                             std::uint64_t seed, const GridShape& grid,
                                             double seconds, double every_s) {
  world::FilamentSimulation sim(map, wind, source, options, seed);
  world::spin_up(sim, options);
  const long long steps = std::max(1LL, std::llround(every_s / options.dt));
  const int frames = static_cast<int>(std::floor(seconds / every_s + 1e-9)) + 1;
  std::vector<std::vector<float>> out;
  std::vector<double> c;
  for (int f = 0; f < frames; ++f) {
    if (f > 0)
      for (long long s = 0; s < steps; ++s)
        sim.step();
    c.assign(grid.size(), 0.0);
    sim.concentration(grid, c);
    out.emplace_back(c.begin(), c.end());
  }
  return out;
}

SinglePlume single_plume(const Map& map, Vec2 source, const PlumeOptions& options,
                         const cfd::FlowOptions& flow, std::uint64_t seed,
                         const std::filesystem::path& wind_dir, double series_s) {
  using Clock = std::chrono::steady_clock;
  check_source(map, source);  // before the flow is solved
  SinglePlume r;
  const auto t0 = Clock::now();
  const cfd::WindField wind =
      wind_dir.empty() ? cfd::solve_wind(map, flow).flow.wind : cfd::read_wind(wind_dir, map);
  const auto t1 = Clock::now();
  const MapPlumes plumes(map, wind, surrogate::feature_grid(map), options);
  r.targets = plumes.run(source, seed);
  if (series_s > 0.0) {
    if (options.model != PlumeSimulator::Filament)
      throw InputError(
          "the advection-diffusion plume is steady: a plume over time needs "
          "--simulator filament");
    r.series.grid = plume_series_grid(map);
    r.series.frames = plume_series(map, wind, source, options.filament, seed, r.series.grid,
                                   series_s, r.series.every_s);
  }
  r.flow_s = std::chrono::duration<double>(t1 - t0).count();
  r.plume_s = std::chrono::duration<double>(Clock::now() - t1).count();
  return r;
}

}  // namespace plumekit::dataset
