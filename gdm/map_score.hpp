#pragma once
// How good a gas map is: against the world's true mean plume (seed 000 App. E's symmetric KL
// distance, and the RMSE), and where it puts the source (seed 000 §8.5.2.1's six estimates).
#include <string>
#include <vector>

#include "cfd/wind_field.hpp"
#include "core/grid.hpp"
#include "core/map.hpp"
#include "gdm/kernel_dmv.hpp"

namespace plumekit::gdm {

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

struct SourceEstimate {
  std::string name;  // "peak mean", "peak variance", ..., "90% area mean", ...
  Vec2 position;     // arena frame
  Vec2 lo, hi;       // the 90 % areas' extent (equal to position for the peaks)
};
// The peaks of the mean, the variance and their product, and the centres of the cells within 90 %
// of each one's maximum.
std::vector<SourceEstimate> source_estimates(const GdmMaps& maps);

}  // namespace plumekit::gdm
