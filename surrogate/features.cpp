#include "surrogate/features.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "map/rasterize.hpp"
#include "surrogate/model_file.hpp"

namespace plumekit::surrogate {

namespace {

// The parts of one arena wall that are not an opening, as segments.
void solid_wall_segments(const Map& map, Side side, std::vector<std::pair<Vec2, Vec2>>& out) {
  const double length = map.wall_length(side);
  std::vector<std::pair<double, double>> gaps;
  for (const Opening& o : map.openings)
    if (map.wall_of(o) == side) gaps.emplace_back(o.lo(), o.hi());
  std::sort(gaps.begin(), gaps.end());
  double s = 0.0;
  for (const auto& [a, b] : gaps) {
    if (a > s) out.emplace_back(map.wall_point(side, s), map.wall_point(side, a));
    s = std::max(s, b);
  }
  if (s < length) out.emplace_back(map.wall_point(side, s), map.wall_point(side, length));
}

}  // namespace

double signed_distance(const Map& map, Vec2 p) {
  double d = std::numeric_limits<double>::infinity();
  for (const Polygon& poly : map.obstacles)
    for (std::size_t k = 0; k < poly.size(); ++k)
      d = std::min(d, distance_to_segment(p, poly[k], poly[(k + 1) % poly.size()]));
  std::vector<std::pair<Vec2, Vec2>> walls;
  for (Side side : {Side::Left, Side::Right, Side::Bottom, Side::Top})
    solid_wall_segments(map, side, walls);
  for (const auto& [a, b] : walls)
    d = std::min(d, distance_to_segment(p, a, b));
  return map.obstacle_at(p) >= 0 ? -d : d;
}

std::vector<float> map_features(const Map& map, const GridShape& shape) {
  const Grid<std::uint8_t> labels = rasterize_labels(map, shape);
  std::vector<float> out(2 * shape.size());
  for (int j = 0; j < shape.ny; ++j)
    for (int i = 0; i < shape.nx; ++i) {
      const std::size_t k = shape.index(i, j);
      out[k] = static_cast<float>(labels.values[k]);
      out[shape.size() + k] = static_cast<float>(signed_distance(map, shape.centre(i, j)));
    }
  return out;
}

GridShape physical_grid(const Map& map, double cell) {
  const int nx = std::max(1, static_cast<int>(std::lround(map.width / cell)));
  const int ny = std::max(1, static_cast<int>(std::lround(map.height / cell)));
  return GridShape{nx, ny, map.width, map.height};
}

std::vector<float> wind_features(const cfd::WindField& wind, const GridShape& shape) {
  std::vector<float> out(2 * shape.size());
  for (int j = 0; j < shape.ny; ++j)
    for (int i = 0; i < shape.nx; ++i) {
      const std::size_t k = shape.index(i, j);
      const Vec2 w = wind.at(shape.centre(i, j));
      out[k] = static_cast<float>(w.x);
      out[shape.size() + k] = static_cast<float>(w.y);
    }
  return out;
}

std::vector<std::string> input_channel_names(double feature_cell, bool physics_input) {
  // The model file's contract names them (the one list); a dataset's channels are a model's inputs.
  return feature_channel_names(feature_cell > 0, feature_cell > 0 && physics_input);
}

PhysicsFeature::PhysicsFeature(const Map& map, const cfd::WindField& wind, const GridShape& grid,
                               const cfd::AdvectionDiffusionOptions& options)
    : ad_(std::make_unique<cfd::AdvectionDiffusion>(wind, options)),
      resampler_(std::make_unique<GridResampler>(ad_->shape(), ad_->solid_mask(), grid)),
      in_obstacle_(grid.size()),
      grid_(grid) {
  for (std::size_t k = 0; k < grid.size(); ++k)
    in_obstacle_[k] = map.obstacle_at(grid.centre(static_cast<int>(k % grid.nx),
                                                  static_cast<int>(k / grid.nx))) >= 0;
}

PhysicsFeature::~PhysicsFeature() = default;

Grid<double> PhysicsFeature::operator()(Vec2 source) const {
  // A point of the map's free space with no free flow cell within three cells: the flow grid
  // closed the gap around it (a narrow nook of a real floor), so no air reaches it there, and the
  // physics plume of a release there is nothing. A model's candidate may lie there; the
  // dataset's sources never do (they are drawn where the flow blows).
  if (ad_->point_weights(source).empty()) return Grid<double>(grid_, 0.0);
  Grid<double> c = resampler_->apply(ad_->solve(source));
  for (std::size_t k = 0; k < c.values.size(); ++k)
    if (in_obstacle_[k]) c.values[k] = 0.0;
  return c;
}

std::vector<float> source_feature(Vec2 source, const GridShape& shape) {
  std::vector<float> out(shape.size());
  for (int j = 0; j < shape.ny; ++j)
    for (int i = 0; i < shape.nx; ++i)
      out[shape.index(i, j)] = static_cast<float>(norm(shape.centre(i, j) - source));
  return out;
}

}  // namespace plumekit::surrogate
