#pragma once
// What `plumekit plan` prints: the JSON summary and the human lines of one
// planned path. A moved start is added by the caller, in the form every
// command that moves a start shares; a moved goal is reported here alike
// ("goal_moved": {"requested", "used"}, absent when not moved).
#include "core/report.hpp"
#include "map/map.hpp"
#include "planner/planner.hpp"

namespace plumekit::planner {

struct PlanTiming {
  double build_ms = 0.0;  // the planner's construction (free space, graph)
  double query_us = 0.0;  // the query
};

// Positions in arena coordinates; the report holds them in `frame`.
Report plan_report(const PlanResult& result, PlannerKind kind, const PlannerOptions& options,
                   Vec2 from, Vec2 to, const PlanTiming& timing, const MapFrame& frame = {});

}  // namespace plumekit::planner
