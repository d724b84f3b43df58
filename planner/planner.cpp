#include "planner/planner.hpp"

#include "core/error.hpp"
#include "core/option_check.hpp"
#include "planner/ompl_planner.hpp"
#include "planner/vg_planner.hpp"

namespace plumekit::planner {

const char* to_string(PlannerKind kind) {
  switch (kind) {
    case PlannerKind::VisibilityGraph:
      return "vg";
    case PlannerKind::RRTstar:
      return "rrtstar";
    case PlannerKind::PRMstar:
      return "prmstar";
  }
  return "?";
}

PlannerKind parse_planner_kind(const std::string& name) {
  for (PlannerKind k : {PlannerKind::VisibilityGraph, PlannerKind::RRTstar, PlannerKind::PRMstar})
    if (name == to_string(k)) return k;
  throw OptionError("planner.kind", "unknown planner '" + name + "' (use vg, rrtstar or prmstar)");
}

const OptionTable<PlannerOptions>& planner_option_table() {
  using O = PlannerOptions;
  static const OptionTable<O> table{
      "Planner (planner::PlannerOptions)",
      {{"planner.margin", "", &O::margin, non_negative(10.0, "m"),
        "Clearance kept off obstacles: the robot's radius plus a safety distance, m",
        "the robot's radius plus a safety distance; the thesis used 0.15 m"},
       {"planner.arc_segments", "", &O::arc_segments, count_range(4, 1024),
        "Sides of the polygon obstacles are inflated by (a multiple of 4 keeps axis-aligned walls "
        "offset by exactly margin)"},
       {"planner.ompl_iterations", "", &O::ompl_iterations, count_range(1, 100'000'000),
        "OMPL planners: iterations at most"},
       {"planner.ompl_time_limit_s", "", &O::ompl_time_limit_s, positive(3600.0, "s"),
        "OMPL planners: time budget, s"},
       {"planner.ompl_target_length", "", &O::ompl_target_length, non_negative(1e6, "m"),
        "OMPL planners: stop once a path this short is found, m (0: use the whole budget)",
        "0 uses the whole budget"},
       {"planner.ompl_simplify",
        "",
        &O::ompl_simplify,
        {},
        "OMPL planners: simplify the path found"}}};
  return table;
}

void PlannerOptions::validate() const {
  plumekit::validate(planner_option_table(), *this);
}

std::unique_ptr<Planner> make_planner(const Map& map, const PlannerOptions& options,
                                      PlannerKind kind) {
  options.validate();
  if (kind == PlannerKind::VisibilityGraph)
    return std::make_unique<VisibilityGraphPlanner>(map, options);
  return std::make_unique<OmplPlanner>(map, options, kind);
}

}  // namespace plumekit::planner
