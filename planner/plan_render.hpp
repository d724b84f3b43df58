#pragma once
// The picture of a planned path: the map, the zone the robot's centre must
// keep out of (tinted), the inflated boundary, the path and its ends.
#include <string>

#include "map/map.hpp"
#include "map/map_render.hpp"
#include "planner/free_space.hpp"
#include "planner/planner.hpp"

namespace plumekit::planner {

// `planner_name` (e.g. "vg") goes into the title with the margin and length.
Picture draw_plan(const Map& map, const FreeSpace& space, const PlanResult& result,
                  const std::string& planner_name, const RenderOptions& options = {});

}  // namespace plumekit::planner
