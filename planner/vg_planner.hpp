#pragma once
// The exact planner: visibility graph of the inflated free space plus A*.
#include "planner/astar.hpp"
#include "planner/free_space.hpp"
#include "planner/planner.hpp"
#include "planner/visibility_graph.hpp"

namespace plumekit::planner {

class VisibilityGraphPlanner : public Planner {
 public:
  VisibilityGraphPlanner(const Map& map, const PlannerOptions& options);

  PlannerKind kind() const override { return PlannerKind::VisibilityGraph; }
  PlanResult plan(Vec2 start, Vec2 goal) const override;

  const FreeSpace& free_space() const { return space_; }
  const VisibilityGraph& graph() const { return graph_; }

 private:
  FreeSpace space_;
  VisibilityGraph graph_;
};

}  // namespace plumekit::planner
