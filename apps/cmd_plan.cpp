// plumekit plan: a collision-free path between two points of a map.
#include <chrono>
#include <iomanip>
#include <sstream>

#include "apps/cli.hpp"
#include "apps/commands.hpp"
#include "core/error.hpp"
#include "core/map_json.hpp"
#include "core/map_render.hpp"
#include "core/output_target.hpp"
#include "planner/free_space.hpp"
#include "planner/plan_render.hpp"
#include "planner/planner.hpp"

namespace plumekit::cli {

namespace {

using nlohmann::ordered_json;
namespace pl = plumekit::planner;

std::string fmt(Vec2 p) {
  std::ostringstream s;
  s << std::setprecision(6) << '(' << p.x << ", " << p.y << ')';
  return s.str();
}

}  // namespace

void add_plan_commands(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "plan", "Shortest collision-free path between two points, keeping a margin off obstacles");
  struct Args {
    std::string map = default_map().string();
    std::string from, to, planner = "vg", out;
    double margin = 0.15;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("MAP", a->map, "Map file (JSON)")->capture_default_str();
  cmd->add_option("--from", a->from, "Start point X,Y in metres")->required();
  cmd->add_option("--to", a->to, "Goal point X,Y in metres")->required();
  bind_field(
      cmd,
      cmd->add_option("--margin", a->margin,
                      "Clearance from obstacles and walls in metres (robot radius + safety)"),
      "planner.margin")
      ->capture_default_str();
  cmd->add_option("--planner", a->planner,
                  "vg (visibility graph + A*, exact), rrtstar or prmstar (OMPL)")
      ->capture_default_str();
  cmd->add_option("--out,-o", a->out, "Also draw the path over the map to this PNG");
  add_common_flags(cmd);
  cmd->callback([a] {
    const Vec2 from = parse_point(a->from, "--from"), to = parse_point(a->to, "--to");
    if (!std::isfinite(a->margin) || a->margin < 0.0)
      throw InputError("--margin: must be a number >= 0 (metres), got " +
                       std::to_string(a->margin));
    pl::PlannerKind kind;
    try {
      kind = pl::parse_planner_kind(a->planner);
    } catch (const InputError&) {
      throw InputError("--planner: unknown planner '" + a->planner +
                       "' (use vg, rrtstar or prmstar)");
    }
    const Map map = read_map(a->map);
    if (!a->out.empty()) check_output_file(a->out, {a->map});
    pl::PlannerOptions options;
    options.margin = a->margin;

    using Clock = std::chrono::steady_clock;
    const auto t0 = Clock::now();
    const auto planner = pl::make_planner(map, options, kind);
    const auto t1 = Clock::now();
    const pl::PlanResult r = planner->plan(from, to);
    const auto t2 = Clock::now();
    const double build_ms = std::chrono::duration<double, std::milli>(t1 - t0).count();
    const double query_us = std::chrono::duration<double, std::micro>(t2 - t1).count();

    if (!a->out.empty()) {
      const pl::FreeSpace space(map, options.margin, options.arc_segments);
      write_png(pl::draw_plan(map, space, r, pl::to_string(kind)), a->out);
    }

    ordered_json path = ordered_json::array();
    for (Vec2 v : r.path)
      path.push_back(point_json(v));
    ordered_json j{{"ok", true},
                   {"map", a->map},
                   {"planner", pl::to_string(kind)},
                   {"margin", a->margin},
                   {"from", point_json(from)},
                   {"to", point_json(to)},
                   {"start", point_json(r.start)},
                   {"goal", point_json(r.goal)},
                   {"start_moved", r.start_moved},
                   {"goal_moved", r.goal_moved},
                   {"path", path},
                   {"length_m", r.length},
                   {"build_ms", build_ms},
                   {"query_us", query_us}};
    if (!a->out.empty()) j["out"] = a->out;

    std::ostringstream human;
    human << pl::to_string(kind) << " path from " << fmt(from) << " to " << fmt(to) << ", margin "
          << a->margin << " m: " << r.path.size() << " vertices, length " << std::setprecision(6)
          << r.length << " m\n";
    for (Vec2 v : r.path)
      human << "  " << fmt(v) << '\n';
    if (r.start_moved)
      human << "start moved to " << fmt(r.start) << " (it was within the margin)\n";
    if (r.goal_moved) human << "goal moved to " << fmt(r.goal) << " (it was within the margin)\n";
    human << "built in " << std::setprecision(3) << build_ms << " ms, query " << query_us << " us";
    if (!a->out.empty()) human << "\nwrote " << a->out;
    report(j, human.str());
  });
}

}  // namespace plumekit::cli
