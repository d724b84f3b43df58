#pragma once
// How good a gas map is against the world's true mean plume (seed 000 App. E's symmetric KL
// distance, and the RMSE): scoring against the truth belongs to the run loop, not to a method.
#include <string>
#include <vector>

#include "cfd/wind_field.hpp"
#include "core/grid.hpp"
#include "map/map.hpp"

namespace plumekit::run {

// The filament world's long-time mean plume of `source` (dataset::filament_world_mean on `wind`),
// read at the centres of `cells`, NaN inside obstacles: what a map of that world should show.
Grid<double> true_mean_plume(const Map& map, const cfd::WindField& wind, Vec2 source,
                             const GridShape& cells);
// Bytes per cell of the maps that scoring them adds: the resampler's interpolation weights of each
// cell, the truth and the scores' copies (measured 100-150 B per cell of peak RSS).
inline constexpr double kScoreBytesPerCell = 160.0;

struct MapScore {
  // 1/2 KL(p|q) + 1/2 KL(q|p) of the two maps, each made a distribution over the cells where both
  // are finite (values below 0 count 0, and every cell gets at least 1e-9 of the mass, so that a
  // cell one map leaves empty does not make it infinite).
  double kl_distance = 0.0;
  double rmse = 0.0;        // of the mean against the truth, concentration units
  double truth_peak = 0.0;  // the truth's largest value, for scale
};
MapScore score_mean(const Grid<double>& mean, const Grid<double>& truth);

}  // namespace plumekit::run
