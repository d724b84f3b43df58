#pragma once
// What every planner does with a query's start and goal before searching:
// reject points inside obstacles or outside the arena, and move a point that is
// only inside the inflated zone to the nearest point that keeps the margin.
#include "planner/free_space.hpp"
#include "planner/planner.hpp"

namespace plumekit::planner {

// Fills requested_*, start, goal and the *_moved flags of `result`. InputError
// when an end is not finite, outside the arena, inside (or on) an obstacle, or
// when there is no free space at all.
void place_endpoints(const FreeSpace& space, Vec2 start, Vec2 goal, PlanResult& result);

// The InputError for a goal that the start cannot reach.
[[noreturn]] void throw_unreachable(const FreeSpace& space, const PlanResult& result);

}  // namespace plumekit::planner
