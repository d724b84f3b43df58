#pragma once
// The CNN's input feature maps on the 64 x 64 grid over the arena (see
// manifest.cpp for the exact contract written into every dataset):
//   0  region labels as floats: inside obstacle 0, free 1, wall 2, inlet 3, outlet 4
//   1  signed distance in metres from the cell centre to the nearest solid
//      surface (obstacle edges and the arena walls outside the openings),
//      computed exactly from the polygons; negative inside obstacles
//   2  Euclidean distance in metres from the cell centre to the source
// Datasets for the v2 surrogate (issue 19, `--feature-cell`) use a physical grid instead, and
// five channels: region, signed distance, the steady wind's u and v in m/s at the cell centre,
// and the source distance. A hybrid model's datasets (issue 46, `--physics-input`) add a sixth
// before the source distance: physics_mean, plumekit's own physics plume for the source.
#include <memory>
#include <string>
#include <vector>

#include "cfd/advection_diffusion.hpp"
#include "cfd/wind_field.hpp"
#include "core/grid.hpp"
#include "core/resample.hpp"
#include "map/map.hpp"

namespace plumekit::surrogate {

inline constexpr int kFeatureGrid = 64;

inline GridShape feature_grid(const Map& map) {
  return GridShape{kFeatureGrid, kFeatureGrid, map.width, map.height};
}

// The v2 grid: nominal cells of `cell` metres over the whole map, max(1, round(W / cell)) columns
// and max(1, round(H / cell)) rows, so a cell is within half a cell over the map's side of `cell`
// (exact when the side is a multiple of it).
GridShape physical_grid(const Map& map, double cell);
// A dataset's grid: the thesis's 64 x 64 one when `feature_cell` is 0, else physical_grid.
inline GridShape sample_grid(const Map& map, double feature_cell) {
  return feature_cell > 0 ? physical_grid(map, feature_cell) : feature_grid(map);
}
// Input channels of a dataset's samples: 3 on the thesis grid, 5 (with the wind) on a physical
// one, 6 with the physics plume too.
inline int input_channels(double feature_cell, bool physics_input = false) {
  return feature_cell > 0 ? (physics_input ? 6 : 5) : 3;
}
// Their names, in order (the source distance last): region, signed_distance, [wind_u, wind_v,
// [physics_mean,]] source_distance.
std::vector<std::string> input_channel_names(double feature_cell, bool physics_input = false);

// Channels 0 and 1: they depend on the map only. [2][ny][nx], row 0 at y = 0.
std::vector<float> map_features(const Map& map, const GridShape& shape);
// The steady wind at each cell centre (WindField::at: 0 inside obstacles), u then v, m/s.
// [2][ny][nx].
std::vector<float> wind_features(const cfd::WindField& wind, const GridShape& shape);
// The source distance channel. [ny][nx].
std::vector<float> source_feature(Vec2 source, const GridShape& shape);
// The physics_mean channel of one map: the steady advection-diffusion plume of a release at the
// source (cfd/advection_diffusion.hpp) in the map's wind, read at the grid's cell centres
// (GridResampler: bilinear among free flow cells), 0 at centres inside obstacles. The operator
// depends on the wind only, so it is factored once here and each source is one forward solve.
// The dataset generator and PlumeNetwork both call it, so a model sees what it was trained on.
class PhysicsFeature {
 public:
  PhysicsFeature(const Map& map, const cfd::WindField& wind, const GridShape& grid,
                 const cfd::AdvectionDiffusionOptions& options);
  ~PhysicsFeature();
  // In concentration units (the targets' units), [ny][nx]; all 0 for a source the flow grid
  // leaves no air at (no free flow cell within three cells). Const: callable from many threads.
  Grid<double> operator()(Vec2 source) const;
  const cfd::AdvectionDiffusion& advection_diffusion() const { return *ad_; }
  // Whether cell k's centre lies inside an obstacle (where the channel is 0).
  bool in_obstacle(std::size_t k) const { return in_obstacle_[k] != 0; }

 private:
  std::unique_ptr<cfd::AdvectionDiffusion> ad_;
  std::unique_ptr<GridResampler> resampler_;
  std::vector<char> in_obstacle_;
  GridShape grid_;
};

// Signed distance from p to the nearest solid surface (see above).
double signed_distance(const Map& map, Vec2 p);

}  // namespace plumekit::surrogate
