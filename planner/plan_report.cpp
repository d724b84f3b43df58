#include "planner/plan_report.hpp"

#include <iomanip>
#include <sstream>

namespace plumekit::planner {

namespace {

using nlohmann::ordered_json;

std::string text_of(Vec2 p) {
  std::ostringstream s;
  s << std::setprecision(6) << '(' << p.x << ", " << p.y << ')';
  return s.str();
}

ordered_json json_of(Vec2 p) {
  return ordered_json::array({p.x, p.y});
}

}  // namespace

Report plan_report(const PlanResult& r, PlannerKind kind, const PlannerOptions& options, Vec2 from,
                   Vec2 to, const PlanTiming& timing, const MapFrame& frame) {
  // Every position is reported in the map's frame.
  auto point_json = [&](Vec2 p) { return json_of(frame.to_frame(p)); };
  auto fmt = [&](Vec2 p) { return text_of(frame.to_frame(p)); };
  ordered_json path = ordered_json::array();
  for (Vec2 v : r.path)
    path.push_back(point_json(v));
  ordered_json j{{"ok", true},
                 {"planner", to_string(kind)},
                 {"margin", options.margin},
                 {"from", point_json(from)},
                 {"to", point_json(to)},
                 {"start", point_json(r.start)},
                 {"goal", point_json(r.goal)},
                 {"path", path},
                 {"length_m", r.length},
                 {"build_ms", timing.build_ms},
                 {"query_us", timing.query_us}};
  if (r.goal_moved)
    j["goal_moved"] = {{"requested", point_json(r.requested_goal)}, {"used", point_json(r.goal)}};

  std::ostringstream human;
  human << to_string(kind) << " path from " << fmt(from) << " to " << fmt(to) << ", margin "
        << options.margin << " m: " << r.path.size() << " vertices, length " << std::setprecision(6)
        << r.length << " m\n";
  for (Vec2 v : r.path)
    human << "  " << fmt(v) << '\n';
  if (r.goal_moved)
    human << "goal moved from " << fmt(r.requested_goal) << " to " << fmt(r.goal)
          << ": closer than the margin to an obstacle\n";
  human << "built in " << std::setprecision(3) << timing.build_ms << " ms, query "
        << timing.query_us << " us";
  return {j, human.str()};
}

}  // namespace plumekit::planner
