#include "planner/planner.hpp"

#include "core/error.hpp"
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
  throw InputError("planner: unknown planner '" + name + "' (use vg, rrtstar or prmstar)");
}

std::unique_ptr<Planner> make_planner(const Map& map, const PlannerOptions& options,
                                      PlannerKind kind) {
  if (kind == PlannerKind::VisibilityGraph)
    return std::make_unique<VisibilityGraphPlanner>(map, options);
  return std::make_unique<OmplPlanner>(map, options, kind);
}

}  // namespace plumekit::planner
