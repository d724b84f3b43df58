#include "planner/plan_render.hpp"

#include <cmath>
#include <iomanip>
#include <sstream>
#include <vector>

#include <opencv2/imgproc.hpp>

namespace plumekit::planner {

namespace {

const cv::Scalar kKeepOutTint(120, 170, 250), kKeepOutEdge(40, 120, 230), kMoved(60, 60, 60);
// The keep-out tint is blended at this weight over free space.
constexpr double kTintWeight = 0.45;

// Every ring (outer boundaries and holes) of the free space, in fixed-point pixels.
std::vector<std::vector<cv::Point>> free_space_rings(const MapCanvas& canvas,
                                                     const FreeSpace& space) {
  std::vector<std::vector<cv::Point>> rings;
  auto add = [&](const Polygon& ring) {
    std::vector<cv::Point> pts;
    for (Vec2 v : ring)
      pts.push_back(canvas.fixed(v));
    rings.push_back(std::move(pts));
  };
  for (const Region& region : space.regions()) {
    add(region.outer);
    for (const Polygon& h : region.holes)
      add(h);
  }
  return rings;
}

std::string plan_title(const Map& map, const FreeSpace& space, const PlanResult& r,
                       const std::string& planner_name) {
  std::ostringstream title;
  title << (map.name.empty() ? "map" : map.name) << ": " << planner_name << " path, margin "
        << space.margin() << " m, length " << std::fixed << std::setprecision(3) << r.length
        << " m";
  return title.str();
}

Frame plan_frame(const Map& map, const FreeSpace& space, const PlanResult& r,
                 const std::string& planner_name) {
  const cv::Scalar tint =
      kKeepOutTint * kTintWeight + cv::Scalar(248, 246, 244) * (1 - kTintWeight);
  std::vector<LegendEntry> legend{{LegendEntry::Symbol::Swatch, tint,
                                   "keep-out zone (margin " +
                                       [&] {
                                         std::ostringstream s;
                                         s << space.margin();
                                         return s.str();
                                       }() +
                                       " m)"},
                                  {LegendEntry::Symbol::Line, colours::kPath, "path"},
                                  {LegendEntry::Symbol::Dot, colours::kStart, "start"},
                                  {LegendEntry::Symbol::Dot, colours::kGoal, "goal"}};
  if (r.start_moved || r.goal_moved)
    legend.push_back({LegendEntry::Symbol::Ring, kMoved, "requested end (moved)"});
  return Frame{plan_title(map, space, r, planner_name), std::nullopt, legend, true};
}

}  // namespace

Picture draw_plan(const Map& map, const FreeSpace& space, const PlanResult& r,
                  const std::string& planner_name, const RenderOptions& options) {
  MapCanvas canvas(map, options, plan_frame(map, space, r, planner_name));
  cv::Mat& img = canvas.image();
  canvas.draw_free_space();
  const auto rings = free_space_rings(canvas, space);
  constexpr int shift = MapCanvas::kFixedShift;
  // Keep-out zone: the arena minus free space (fillPoly's even-odd rule
  // carves the free pieces, holes and all, out of the arena).
  cv::Mat keep_out(img.size(), CV_8U, cv::Scalar(0));
  cv::rectangle(keep_out, canvas.arena_rect(), cv::Scalar(255), cv::FILLED);
  if (!rings.empty()) cv::fillPoly(keep_out, rings, cv::Scalar(0), cv::LINE_8, shift);
  cv::Mat tinted = img.clone();
  tinted.setTo(kKeepOutTint, keep_out);
  cv::addWeighted(tinted, kTintWeight, img, 1 - kTintWeight, 0.0, img);
  canvas.draw_obstacles();
  cv::polylines(img, rings, true, kKeepOutEdge, 1, cv::LINE_AA, shift);
  canvas.draw_walls_and_openings();
  canvas.draw_sources();

  canvas.draw_path(r.path, colours::kPath, 3);
  const int vertex = static_cast<int>(std::lround(3 * canvas.mark_scale()));
  for (Vec2 v : r.path)
    cv::circle(img, canvas.pixel(v), vertex, colours::kPath, cv::FILLED, cv::LINE_AA);
  // A moved end: a thin line from where it was asked for to where it went.
  auto moved = [&](Vec2 from, Vec2 to) {
    cv::line(img, canvas.fixed(from), canvas.fixed(to), kMoved, 1, cv::LINE_AA, shift);
    canvas.draw_ring(from, kMoved);
  };
  if (r.start_moved) moved(r.requested_start, r.start);
  if (r.goal_moved) moved(r.requested_goal, r.goal);
  canvas.draw_marker(r.start, colours::kStart, 7);
  canvas.draw_marker(r.goal, colours::kGoal, 7);
  return canvas.finish();
}

}  // namespace plumekit::planner
