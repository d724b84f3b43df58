#include "planner/endpoints.hpp"

#include <sstream>

#include "core/error.hpp"

namespace plumekit::planner {

namespace {

Vec2 place(const FreeSpace& space, Vec2 p, const char* which, bool& moved) {
  const Map& map = space.map();
  if (!is_finite(p))
    throw InputError(std::string("planner: ") + which + " " + to_string(p) +
                     " is not a finite point");
  if (!map.in_arena(p)) {
    std::ostringstream s;
    s << "planner: " << which << ' ' << to_string(p) << " lies outside the arena [0, " << map.width
      << "] x [0, " << map.height << ']';
    throw InputError(s.str());
  }
  if (const int k = map.obstacle_at(p); k >= 0)
    throw InputError(std::string("planner: ") + which + " " + to_string(p) +
                     " lies inside obstacles[" + std::to_string(k) + "]");
  if (space.empty()) {
    std::ostringstream s;
    s << "planner: no free space at margin " << space.margin()
      << " m: the arena is narrower than twice the margin, or the obstacles fill it";
    throw InputError(s.str());
  }
  const Vec2 q = space.nearest_free(p);
  moved = q != p;
  return q;
}

}  // namespace

void place_endpoints(const FreeSpace& space, Vec2 start, Vec2 goal, PlanResult& result) {
  result.requested_start = start;
  result.requested_goal = goal;
  result.start = place(space, start, "start", result.start_moved);
  result.goal = place(space, goal, "goal", result.goal_moved);
}

void throw_unreachable(const FreeSpace& space, const PlanResult& result) {
  std::ostringstream s;
  s << "planner: goal " << to_string(result.requested_goal) << " cannot be reached from start "
    << to_string(result.requested_start) << " keeping a margin of " << space.margin() << " m";
  throw InputError(s.str());
}

}  // namespace plumekit::planner
