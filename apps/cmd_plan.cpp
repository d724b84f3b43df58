// plumekit plan: a collision-free path between two points of a map.
#include <chrono>

#include "apps/cli.hpp"
#include "apps/commands.hpp"
#include "core/error.hpp"
#include "core/output_target.hpp"
#include "map/map_json.hpp"
#include "map/map_render.hpp"
#include "planner/free_space.hpp"
#include "planner/plan_render.hpp"
#include "planner/plan_report.hpp"
#include "planner/planner.hpp"

namespace plumekit::cli {

namespace {

using nlohmann::ordered_json;
namespace pl = plumekit::planner;

}  // namespace

void add_plan_commands(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "plan", "Shortest collision-free path between two points, keeping a margin off obstacles");
  struct Args {
    std::string map, from, to, out;
    std::string planner = pl::to_string(pl::PlannerKind::VisibilityGraph);
    pl::PlannerOptions options;
  };
  auto a = std::make_shared<Args>();
  add_map_argument(cmd, a->map);
  cmd->add_option("--from", a->from, "Start point X,Y in metres")->required();
  cmd->add_option("--to", a->to, "Goal point X,Y in metres")->required();
  bind_field(cmd,
             cmd->add_option("--margin", a->options.margin,
                             "Clearance from obstacles and walls in metres (robot radius + "
                             "safety)"),
             "planner.margin")
      ->capture_default_str();
  bind_field(cmd,
             cmd->add_option("--planner", a->planner,
                             "vg (visibility graph + A*, exact), rrtstar or prmstar (OMPL)"),
             "planner.kind")
      ->capture_default_str();
  cmd->add_option("--out,-o", a->out, "Also draw the path over the map to this PNG");
  add_common_flags(cmd);
  cmd->callback([a] {
    // Points are typed in the map's frame (its file's coordinates).
    const Vec2 from_typed = parse_point(a->from, "--from"), to_typed = parse_point(a->to, "--to");
    const pl::PlannerKind kind = pl::parse_planner_kind(a->planner);
    a->options.validate();
    const Map map = read_map(a->map);
    const Vec2 from = map.from_frame(from_typed), to = map.from_frame(to_typed);
    if (!a->out.empty()) check_output_file(a->out, {a->map});

    using Clock = std::chrono::steady_clock;
    const auto t0 = Clock::now();
    const auto planner = pl::make_planner(map, a->options, kind);
    const auto t1 = Clock::now();
    const pl::PlanResult r = planner->plan(from, to);
    const auto t2 = Clock::now();
    const pl::PlanTiming timing{std::chrono::duration<double, std::milli>(t1 - t0).count(),
                                std::chrono::duration<double, std::micro>(t2 - t1).count()};

    if (!a->out.empty()) {
      const pl::FreeSpace space(map, a->options.margin, a->options.arc_segments);
      write_png(pl::draw_plan(map, space, r, pl::to_string(kind)), a->out);
    }
    Report rep = pl::plan_report(r, kind, a->options, from, to, timing, map.frame);
    ordered_json j{{"ok", true}, {"map", a->map}};
    j.update(rep.json);
    if (r.start_moved) {
      add_moved_start(j, map.to_frame(r.requested_start), map.to_frame(r.start));
      rep.text += "\n" + moved_start_text(map.to_frame(r.requested_start), map.to_frame(r.start));
    }
    if (!a->out.empty()) {
      j["out"] = a->out;
      rep.text += "\nwrote " + a->out;
    }
    report(j, rep.text);
  });
}

}  // namespace plumekit::cli
