#include "dataset/plume.hpp"

#include "core/error.hpp"

namespace plumekit::dataset {

const char* to_string(PlumeModel m) {
  return m == PlumeModel::Filament ? "filament" : "advection-diffusion";
}

PlumeModel parse_plume_model(const std::string& name) {
  if (name == "filament") return PlumeModel::Filament;
  if (name == "advection-diffusion") return PlumeModel::AdvectionDiffusion;
  throw InputError("unknown plume model '" + name + "' (filament or advection-diffusion)");
}

MapPlumes::MapPlumes(const Map& map, const cfd::WindField& wind, const GridShape& sensors,
                     const PlumeOptions& options)
    : map_(map), wind_(wind), sensors_(sensors), options_(options) {
  if (options.model == PlumeModel::AdvectionDiffusion)
    ad_ = std::make_unique<AdvectionDiffusion>(wind, options.advection_diffusion);
}

MapPlumes::~MapPlumes() = default;

PlumeTargets MapPlumes::run(Vec2 source, std::uint64_t seed) const {
  if (!map_.is_free(source))
    throw InputError("source " + to_string(source) + " is outside the arena or inside an obstacle");
  PlumeTargets t;
  if (ad_) {
    t.mean = resample(*ad_, ad_->solve(source), sensors_);
    t.std = Grid<double>(sensors_, 0.0);
    for (int j = 0; j < sensors_.ny; ++j)
      for (int i = 0; i < sensors_.nx; ++i)
        if (map_.obstacle_at(sensors_.centre(i, j)) >= 0) t.mean(i, j) = 0.0;
    return t;
  }
  SensorRecord r = simulate_filaments(map_, wind_, source, sensors_, options_.filament, seed);
  t.mean = std::move(r.mean);
  t.std = std::move(r.std);
  t.filament = r.summary;
  return t;
}

}  // namespace plumekit::dataset
