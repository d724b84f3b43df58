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

void PlannerOptions::validate() const {
  check_non_negative("planner.margin", margin, 10.0, "m",
                     "the robot's radius plus a safety distance; the thesis used 0.15 m");
  check_count("planner.arc_segments", arc_segments, 4, 1024, "the default is 16");
  check_count("planner.ompl_iterations", ompl_iterations, 1, 100'000'000, "the default is 3000");
  check_positive("planner.ompl_time_limit_s", ompl_time_limit_s, 3600.0, "s", "the default is 2 s");
  check_non_negative("planner.ompl_target_length", ompl_target_length, 1e6, "m",
                     "0 uses the whole budget");
}

std::unique_ptr<Planner> make_planner(const Map& map, const PlannerOptions& options,
                                      PlannerKind kind) {
  options.validate();
  if (kind == PlannerKind::VisibilityGraph)
    return std::make_unique<VisibilityGraphPlanner>(map, options);
  return std::make_unique<OmplPlanner>(map, options, kind);
}

}  // namespace plumekit::planner
