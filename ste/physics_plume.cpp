#include "ste/physics_plume.hpp"

#include "core/error.hpp"

namespace plumekit::ste {

PhysicsPlume::PhysicsPlume(const Map& map, const cfd::WindField& wind, const PhysicsPlumeOptions& o)
    : parameters_{{"x", 0.0, map.width},
                  {"y", 0.0, map.height},
                  {"release_scale", o.scale_lo, o.scale_hi}},
      // Validated before the source grid is sized by o.source_cell.
      candidates_((o.validate(), GridShape::with_cell(map.width, map.height, o.source_cell))),
      allowed_(free_cells(map, candidates_, 0.0)),
      ad_(std::make_unique<cfd::AdvectionDiffusion>(wind, o.advection_diffusion)) {
  // A cell whose centre is free but falls in a solid flow cell cannot hold a source.
  for (int j = 0; j < candidates_.ny; ++j)
    for (int i = 0; i < candidates_.nx; ++i) {
      const Vec2 c = candidates_.centre(i, j);
      const GridShape& f = ad_->shape();
      const int fi = std::min(f.nx - 1, static_cast<int>(c.x / f.dx()));
      const int fj = std::min(f.ny - 1, static_cast<int>(c.y / f.dy()));
      if (ad_->solid(fi, fj)) allowed_[candidates_.index(i, j)] = 0;
    }
  resampler_ = std::make_unique<GridResampler>(ad_->shape(), ad_->solid_mask(), candidates_);
}

std::vector<double> PhysicsPlume::readings_at(Vec2 p) const {
  const Grid<double> r = resampler_->apply(ad_->adjoint(p));
  std::vector<double> out(r.values);
  for (std::size_t k = 0; k < out.size(); ++k)
    if (!allowed_[k]) out[k] = 0.0;
  return out;
}

}  // namespace plumekit::ste
