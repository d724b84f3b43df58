#pragma once
// The physics plume model: steady advection-diffusion in the map's solved
// wind (cfd/advection_diffusion.hpp), the exact mean of the generator's
// own physics. One transposed (adjoint) solve per sensor position gives that
// position's reading for every candidate source at once, so readings_at costs
// one sparse triangular solve pair on the flow grid plus a resampling.
#include <memory>

#include "cfd/advection_diffusion.hpp"
#include "cfd/wind_field.hpp"
#include "core/resample.hpp"
#include "ste/forward_model.hpp"

namespace plumekit::ste {

struct PhysicsPlumeOptions {
  // Candidate source cells, metres (0.1 m: 100 x 40 on the 10 x 4 arena).
  double source_cell = 0.1;
  // Eddy diffusivity and release rate: the dataset's advection-diffusion
  // defaults (D = 0.05 m^2/s equals the filament model's equivalent
  // diffusivity without its meander; release 1000). Its decay rate is the
  // filament world's: 1 / lifetime_s() = 1/28 s, the rate at which the world
  // loses its gas (docs/validation.md, "Floors"); without it the model fills
  // dead-end rooms the world never fills.
  cfd::AdvectionDiffusionOptions advection_diffusion = world_matched();
  // Prior bounds of the release scale (1 = the dataset's release rate).
  double scale_lo = 1.0, scale_hi = 1.0;
  // OptionError naming the field (docs/methods.md, "Options"); ste/options.cpp.
  void validate() const;
  // The world's decay as a number, not an include: the estimator never reads the world. A test
  // ties it to the world's filament lifetime (dataset::filament_world_mean()).
  static constexpr double kWorldLifetimeS = 28.0;
  static cfd::AdvectionDiffusionOptions world_matched() {
    cfd::AdvectionDiffusionOptions o;
    o.decay_rate = 1.0 / kWorldLifetimeS;
    return o;
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
  const cfd::AdvectionDiffusion& operator_() const { return *ad_; }

 private:
  std::vector<Parameter> parameters_;
  GridShape candidates_;
  std::vector<std::uint8_t> allowed_;
  std::unique_ptr<cfd::AdvectionDiffusion> ad_;
  std::unique_ptr<GridResampler> resampler_;  // flow grid -> source cells, built once
};

}  // namespace plumekit::ste
