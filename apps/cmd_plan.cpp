// plumekit plan: a collision-free path between two points of a map.
#include <chrono>
#include <iomanip>
#include <sstream>

#include <opencv2/imgproc.hpp>

#include "apps/cli.hpp"
#include "apps/commands.hpp"
#include "core/error.hpp"
#include "core/map_json.hpp"
#include "core/map_render.hpp"
#include "core/output_target.hpp"
#include "planner/free_space.hpp"
#include "planner/planner.hpp"

namespace plumekit::cli {

namespace {

using nlohmann::ordered_json;
namespace pl = plumekit::planner;

cv::Point fixed(const MapCanvas& canvas, Vec2 p) {
  const cv::Point2d q = canvas.to_px(p);
  return {static_cast<int>(std::lround(q.x * 16)), static_cast<int>(std::lround(q.y * 16))};
}

// The map, the zone the robot's centre must keep out of (tinted), the inflated
// boundary, the path and its ends.
cv::Mat draw_plan(const Map& map, const pl::FreeSpace& space, const pl::PlanResult& r,
                  const std::string& title) {
  MapCanvas canvas(map);
  cv::Mat& img = canvas.image();
  canvas.draw_free_space();

  std::vector<std::vector<cv::Point>> rings;
  for (const pl::Region& region : space.regions()) {
    for (const Polygon* ring = &region.outer; ring;) {
      std::vector<cv::Point> pts;
      for (Vec2 v : *ring)
        pts.push_back(fixed(canvas, v));
      rings.push_back(std::move(pts));
      ring = nullptr;
    }
    for (const Polygon& h : region.holes) {
      std::vector<cv::Point> pts;
      for (Vec2 v : h)
        pts.push_back(fixed(canvas, v));
      rings.push_back(std::move(pts));
    }
  }
  // Keep-out zone: the arena minus free space (fillPoly's even-odd rule
  // carves the free pieces, holes and all, out of the arena).
  cv::Mat keep_out(img.size(), CV_8U, cv::Scalar(0));
  cv::rectangle(keep_out, canvas.pixel({0, map.height}), canvas.pixel({map.width, 0}),
                cv::Scalar(255), cv::FILLED);
  if (!rings.empty()) cv::fillPoly(keep_out, rings, cv::Scalar(0), cv::LINE_8, 4);
  cv::Mat tinted = img.clone();
  tinted.setTo(cv::Scalar(120, 170, 250), keep_out);
  cv::addWeighted(tinted, 0.45, img, 0.55, 0.0, img);
  canvas.draw_obstacles();
  cv::polylines(img, rings, true, cv::Scalar(40, 120, 230), 1, cv::LINE_AA, 4);
  canvas.draw_walls_and_openings();
  canvas.draw_sources();
  canvas.draw_axes_and_scale();

  std::vector<cv::Point> path;
  for (Vec2 v : r.path)
    path.push_back(fixed(canvas, v));
  cv::polylines(img, std::vector<std::vector<cv::Point>>{path}, false, cv::Scalar(170, 60, 20), 3,
                cv::LINE_AA, 4);
  for (Vec2 v : r.path)
    cv::circle(img, fixed(canvas, v), 3 * 16, cv::Scalar(170, 60, 20), cv::FILLED, cv::LINE_AA, 4);
  // A moved end: a thin line from where it was asked for to where it went.
  auto moved = [&](Vec2 from, Vec2 to) {
    cv::line(img, fixed(canvas, from), fixed(canvas, to), cv::Scalar(60, 60, 60), 1, cv::LINE_AA,
             4);
    cv::circle(img, fixed(canvas, from), 5 * 16, cv::Scalar(60, 60, 60), 1, cv::LINE_AA, 4);
  };
  if (r.start_moved) moved(r.requested_start, r.start);
  if (r.goal_moved) moved(r.requested_goal, r.goal);
  canvas.draw_marker(r.start, cv::Scalar(40, 160, 40), 7);
  canvas.draw_marker(r.goal, cv::Scalar(170, 40, 170), 7);  // purple: sources are red
  canvas.draw_title(title);
  return img.clone();
}

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
      std::ostringstream title;
      title << (map.name.empty() ? "map" : map.name) << ": " << pl::to_string(kind)
            << " path, margin " << a->margin << " m, length " << std::fixed << std::setprecision(3)
            << r.length << " m";
      write_png(draw_plan(map, space, r, title.str()), a->out);
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
