#pragma once
// The wind as a picture: speed colour map, streamlines, obstacles, a colour bar.
#include <opencv2/core.hpp>

#include "cfd/wind_field.hpp"
#include "map/map.hpp"
#include "map/map_render.hpp"

namespace plumekit::cfd {

Picture draw_wind(const Map& map, const WindField& wind, const RenderOptions& options = {});
// The image alone.
cv::Mat render_wind(const Map& map, const WindField& wind, double px_per_m = 100.0);

}  // namespace plumekit::cfd
