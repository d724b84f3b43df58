#include "planner/vg_planner.hpp"

#include "planner/endpoints.hpp"

namespace plumekit::planner {

VisibilityGraphPlanner::VisibilityGraphPlanner(const Map& map, const PlannerOptions& options)
    : space_(map, options.margin, options.arc_segments), graph_(space_) {}

PlanResult VisibilityGraphPlanner::plan(Vec2 start, Vec2 goal) const {
  PlanResult r;
  place_endpoints(space_, start, goal, r);
  Search found = shortest_path(graph_, r.start, r.goal);
  if (!found.found) throw_unreachable(space_, r);
  r.path = std::move(found.path);
  r.length = found.length;
  r.expanded = found.expanded;
  return r;
}

}  // namespace plumekit::planner
