// The planner (planner/): shortest collision-free paths with a clearance.
#include <memory>

#include <pybind11/stl.h>

#include "planner/planner.hpp"
#include "python/bindings.hpp"
#include "python/convert.hpp"
#include "python/options.hpp"

namespace plumekit::python {

namespace {

using planner::PlannerOptions;

// A planner with its map, so that paths come back in the map's frame.
struct MapPlanner {
  Map map;
  std::unique_ptr<planner::Planner> planner;
};

py::dict plan_dict(const Map& map, const planner::PlanResult& r) {
  py::list path;
  for (const Vec2& p : r.path)
    path.append(from_point(map.to_frame(p)));
  py::dict out;
  out["path"] = path;
  out["length"] = r.length;
  out["start"] = from_point(map.to_frame(r.start));
  out["goal"] = from_point(map.to_frame(r.goal));
  out["start_moved"] = r.start_moved;
  out["goal_moved"] = r.goal_moved;
  return out;
}

py::dict plan_on(const MapPlanner& p, const py::handle& start, const py::handle& goal) {
  const Vec2 a = p.map.from_frame(to_point(start, "start"));
  const Vec2 b = p.map.from_frame(to_point(goal, "goal"));
  planner::PlanResult r;
  {
    ReleasedGil release;
    r = p.planner->plan(a, b);
  }
  return plan_dict(p.map, r);
}

std::shared_ptr<MapPlanner> make(const Map& map, const std::string& kind, const PlannerOptions& o) {
  auto p = std::make_shared<MapPlanner>();
  p->map = map;
  ReleasedGil release;
  p->planner = planner::make_planner(p->map, o, planner::parse_planner_kind(kind));
  return p;
}

}  // namespace

void bind_planner(py::module_& m) {
  py::class_<PlannerOptions> c(m, "PlannerOptions",
                               "Options of the planner (docs/design/planner.md, \"Options\")");
  c.def(py::init<>());
  bind_table(c, planner::planner_option_table());

  py::class_<MapPlanner, std::shared_ptr<MapPlanner>>(
      m, "Planner",
      "A planner built once for a map (`plumekit plan`): the inflated free space and, for 'vg', "
      "the visibility graph.")
      .def(py::init([](const Map& map, const std::string& kind, const py::object& options,
                       const py::kwargs& kw) {
             return make(map, kind, options_from<PlannerOptions>(options, kw, "Planner"));
           }),
           py::arg("map"), py::arg("kind") = "vg", py::arg("options") = py::none(),
           "`kind`: 'vg' (exact visibility graph), 'rrtstar' or 'prmstar' (OMPL). Keyword "
           "arguments set PlannerOptions fields (margin=0.15).")
      .def("plan", &plan_on, py::arg("start"), py::arg("goal"),
           "The path from start to goal (map frame): a dict with 'path' [(x, y), ...], 'length' "
           "(m), the 'start' and 'goal' used, and whether either was moved off the margin.");
  m.def(
      "plan",
      [](const Map& map, const py::handle& start, const py::handle& goal, const std::string& kind,
         const py::object& options, const py::kwargs& kw) {
        return plan_on(*make(map, kind, options_from<PlannerOptions>(options, kw, "plan")), start,
                       goal);
      },
      py::arg("map"), py::arg("start"), py::arg("goal"), py::arg("kind") = "vg",
      py::arg("options") = py::none(), "One path (Planner(map).plan(start, goal)).");
}

}  // namespace plumekit::python
