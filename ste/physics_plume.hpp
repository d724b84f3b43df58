#pragma once
// The physics plume model: steady advection-diffusion in the map's solved
// wind (dataset/advection_diffusion.hpp), the exact mean of the generator's
// own physics. One transposed (adjoint) solve per sensor position gives that
// position's reading for every candidate source at once, so readings_at costs
// one sparse triangular solve pair on the flow grid plus a resampling.
#include <memory>

#include "cfd/wind_field.hpp"
#include "core/resample.hpp"
#include "dataset/advection_diffusion.hpp"
#include "dataset/filament_model.hpp"
#include "dataset/plume.hpp"
#include "ste/forward_model.hpp"

namespace plumekit::ste {

struct PhysicsPlumeOptions {
  // Candidate source cells, metres (0.1 m: 100 x 40 on the 10 x 4 arena).
  double source_cell = 0.1;
  // Eddy diffusivity and release rate: the dataset's advection-diffusion
  // defaults (D = 0.05 m^2/s equals the filament model's equivalent
  // diffusivity without its meander; release 1000). Its decay rate is the
  // filament world's: 1 / lifetime_s() = 1/28 s, the rate at which the world
  // loses its gas (ste/README.md, "Floors"); without it the model fills
  // dead-end rooms the world never fills.
  dataset::AdvectionDiffusionOptions advection_diffusion = world_matched();
  // Prior bounds of the release scale (1 = the dataset's release rate).
  double scale_lo = 1.0, scale_hi = 1.0;
  // OptionError naming the field (ste/README.md, "Options"); ste/options.cpp.
  void validate() const;
  static dataset::AdvectionDiffusionOptions world_matched() {
    return dataset::filament_world_mean();
  }
};

class PhysicsPlume final : public SourceTableModel {
 public:
  PhysicsPlume(const Map& map, const cfd::WindField& wind, const PhysicsPlumeOptions& options = {});
  std::string name() const override { return "physics"; }
  const std::vector<Parameter>& parameters() const override { return parameters_; }
  const GridShape& candidates() const override { return candidates_; }
  const std::vector<std::uint8_t>& allowed() const override { return allowed_; }
  std::vector<double> readings_at(Vec2 p) const override;
  const dataset::AdvectionDiffusion& operator_() const { return *ad_; }

 private:
  std::vector<Parameter> parameters_;
  GridShape candidates_;
  std::vector<std::uint8_t> allowed_;
  std::unique_ptr<dataset::AdvectionDiffusion> ad_;
  std::unique_ptr<GridResampler> resampler_;  // flow grid -> source cells, built once
};

}  // namespace plumekit::ste
