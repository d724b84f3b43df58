#pragma once
// Sampling-based alternatives to the VG: OMPL's RRT* and PRM* on the same
// inflated free space, with the same exact segment test as their motion
// validator, and OMPL's path simplification. OMPL types stay in the .cpp.
#include "planner/free_space.hpp"
#include "planner/planner.hpp"

namespace plumekit::planner {

class OmplPlanner : public Planner {
 public:
  // `kind` is RRTstar or PRMstar.
  OmplPlanner(const Map& map, const PlannerOptions& options, PlannerKind kind);

  PlannerKind kind() const override { return kind_; }
  // Runs OMPL afresh for each query: a path of the budget's quality, not the
  // shortest. InputError when no path is found within the budget.
  PlanResult plan(Vec2 start, Vec2 goal) const override;

  const FreeSpace& free_space() const { return space_; }

 private:
  FreeSpace space_;
  PlannerOptions options_;
  PlannerKind kind_;
};

}  // namespace plumekit::planner
