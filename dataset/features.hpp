#pragma once
// The CNN's input feature maps on the 64 x 64 grid over the arena (see
// manifest.cpp for the exact contract written into every dataset):
//   0  region labels as floats: inside obstacle 0, free 1, wall 2, inlet 3, outlet 4
//   1  signed distance in metres from the cell centre to the nearest solid
//      surface (obstacle edges and the arena walls outside the openings),
//      computed exactly from the polygons; negative inside obstacles
//   2  Euclidean distance in metres from the cell centre to the source
#include <vector>

#include "core/grid.hpp"
#include "core/map.hpp"

namespace plumekit::dataset {

inline constexpr int kFeatureGrid = 64;

inline GridShape feature_grid(const Map& map) {
  return GridShape{kFeatureGrid, kFeatureGrid, map.width, map.height};
}

// Channels 0 and 1: they depend on the map only. [2][ny][nx], row 0 at y = 0.
std::vector<float> map_features(const Map& map, const GridShape& shape);
// Channel 2. [ny][nx].
std::vector<float> source_feature(Vec2 source, const GridShape& shape);
// Signed distance from p to the nearest solid surface (see above).
double signed_distance(const Map& map, Vec2 p);

}  // namespace plumekit::dataset
