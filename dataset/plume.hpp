#pragma once
// One map's plumes on the sensor grid, by either model: the dispatch the
// dataset generator and `plumekit plume` share. The advection-diffusion
// operator is factored once here, in the constructor, for all sources.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "cfd/wind_field.hpp"
#include "core/grid.hpp"
#include "core/map.hpp"
#include "dataset/advection_diffusion.hpp"
#include "dataset/filament_model.hpp"

namespace plumekit::dataset {

enum class PlumeModel { Filament, AdvectionDiffusion };
const char* to_string(PlumeModel m);
PlumeModel parse_plume_model(const std::string& name);  // InputError naming the value

struct PlumeOptions {
  PlumeModel model = PlumeModel::Filament;
  FilamentOptions filament;
  AdvectionDiffusionOptions advection_diffusion;
  // Validates both models' options (the unused model's too: a dataset's
  // parameters.json records them all). OptionError naming the field.
  void validate() const;
};

struct PlumeTargets {
  Grid<double> mean;
  Grid<double> std;  // all zero for advection-diffusion: its plume is the exact mean
  FilamentSummary filament;
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
  std::unique_ptr<AdvectionDiffusion> ad_;
  // Advection-diffusion only, per map: the sensor weights, and which
  // sensors lie inside obstacles.
  std::unique_ptr<Resampler> resampler_;
  std::vector<char> in_obstacle_;
};

}  // namespace plumekit::dataset
