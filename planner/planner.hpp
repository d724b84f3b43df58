#pragma once
// The planner interface, in OMPL's style: one small abstract class, one
// algorithm per file, every algorithm used through the same call.
//
//   auto planner = plumekit::planner::make_planner(map, {});          // VG + A*
//   PlanResult r = planner->plan({0.5, 2.0}, {9.0, 2.0});
//   r.path, r.length
//
// Errors (start or goal inside an obstacle or outside the arena, an
// unreachable goal) are plumekit::InputError with a message naming the point.
#include <memory>
#include <string>
#include <vector>

#include "core/geometry.hpp"
#include "core/option_table.hpp"
#include "map/map.hpp"

namespace plumekit::planner {

enum class PlannerKind { VisibilityGraph, RRTstar, PRMstar };

const char* to_string(PlannerKind kind);
// "vg", "rrtstar", "prmstar"; InputError naming the value otherwise.
PlannerKind parse_planner_kind(const std::string& name);

struct PlannerOptions {
  // Clearance kept from obstacles and walls, in metres: the robot's radius plus
  // a safety distance. The source thesis used 0.15 m. 0 plans on the raw map.
  double margin = 0.15;
  // Obstacles are inflated by a regular polygon with this many sides that
  // circumscribes the disk of radius `margin`, so the inflated zone contains
  // the exact offset. Over-inflation is at most margin * (1/cos(pi/N) - 1):
  // 2.9 mm for N = 16 and margin 0.15. A multiple of 4 (at least 4) keeps
  // axis-aligned walls offset by exactly `margin`.
  int arc_segments = 16;

  // OMPL planners only. A run stops after this many iterations, after this
  // much wall time, or as soon as it holds a path no longer than
  // `ompl_target_length` (0: use the whole budget), whichever comes first.
  int ompl_iterations = 3000;
  double ompl_time_limit_s = 2.0;
  double ompl_target_length = 0.0;
  // Shortcut and smooth the OMPL path (OMPL's PathSimplifier) before returning it.
  bool ompl_simplify = true;

  // OptionError naming the field ("planner.margin", ...) and its range
  // (docs/options.md; docs/design/planner.md, "Options"); make_planner() calls it.
  void validate() const;
};

// Its options table (core/option_table.hpp): validate() and docs/options.md.
const OptionTable<PlannerOptions>& planner_option_table();

struct PlanResult {
  std::vector<Vec2> path;  // from `start` to `goal`; at least two points
  double length = 0.0;     // metres, along `path`
  // Where the query asked to go, and where the path starts and ends. A point
  // inside the inflated zone (but not inside an obstacle) is moved to the
  // nearest point that keeps the margin; the flags say so.
  Vec2 requested_start, requested_goal;
  Vec2 start, goal;
  bool start_moved = false;
  bool goal_moved = false;
  // VG: nodes A* closed. OMPL: termination checks, about one per iteration.
  int expanded = 0;
};

class Planner {
 public:
  virtual ~Planner() = default;
  virtual PlannerKind kind() const = 0;
  // The shortest (VG) or a short (OMPL) collision-free path. InputError when
  // an end is inside an obstacle or outside the arena, or the goal cannot be
  // reached from the start.
  virtual PlanResult plan(Vec2 start, Vec2 goal) const = 0;
};

// Builds the inflated free space (and, for the VG, the graph) once for `map`.
std::unique_ptr<Planner> make_planner(const Map& map, const PlannerOptions& options = {},
                                      PlannerKind kind = PlannerKind::VisibilityGraph);

}  // namespace plumekit::planner
