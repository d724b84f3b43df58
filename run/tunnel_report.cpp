#include "run/tunnel_report.hpp"
#include "methods/registry.hpp"

#include <algorithm>
#include <cstdio>
#include <sstream>

#include <opencv2/imgproc.hpp>

#include "core/csv.hpp"
#include "core/option_check.hpp"
#include "core/statistics.hpp"
#include "methods/registry.hpp"
#include "run/render.hpp"

namespace plumekit::run {

namespace {

using nlohmann::ordered_json;

ordered_json point_json(Vec3 p) {
  return ordered_json::array({p.x, p.y, p.z});
}

std::string fixed(double v, int digits) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}

double share(const std::vector<TunnelRun>& runs, bool (*test)(const TunnelRun&)) {
  if (runs.empty()) return 0.0;
  return static_cast<double>(std::count_if(runs.begin(), runs.end(), test)) / runs.size();
}

bool succeeded(const TunnelRun& r) {
  return is_tracker(r.method) ? r.found() : r.error_m() <= 0.5;
}

// A phase's colour in the pictures (BGR).
cv::Scalar phase_colour(const std::string& phase) {
  if (phase == "surge") return {40, 150, 40};
  if (phase == "spiral" || phase == "cast") return {0, 140, 255};
  return colours::kPath;  // STE's samples, the Lévy walk
}

}  // namespace

ordered_json tunnel_settings(const TunnelOptions& o) {
  ordered_json j{{"method", o.method},
                 {"tunnel_m", {o.tunnel.length, o.tunnel.width, o.tunnel.height}},
                 {"wind_m_s", o.tunnel.speed},
                 {"release_rate", o.world.filament.release_rate},
                 {"noise", o.world.noise},
                 {"sensor", o.world.sensor.ideal() ? "ideal" : "with response"}};
  if (is_tracker(o.method)) {
    j["speed_m_s"] = o.tracker_speed;
    j["decision_s"] = o.decision_s;
    j["threshold"] = o.search.threshold;
    j["time_limit_s"] = o.time_limit_s;
    j["box_m"] = o.box;
    j["start_downwind_m"] = o.start_downwind;
  } else {
    j["sigma_m"] = o.ste.likelihood.sigma_m;
    j["mh_iterations"] = o.ste.mh.iterations;
    j["step_m"] = o.ste.step;
    j["alpha"] = o.ste.alpha;
    j["max_samples"] = o.ste.max_samples;
  }
  return j;
}

ordered_json tunnel_run_json(const TunnelRun& r, bool steps) {
  const Vec3 e = r.error();
  ordered_json j{{"method", r.method},           {"source", point_json(r.source)},
                 {"start", point_json(r.start)}, {"estimate", point_json(r.estimate)},
                 {"error_m", r.error_m()},       {"error_xyz_m", point_json(e)},
                 {"closest_m", r.closest_m()},   {"time_within_0_5m_s", r.time_within(0.5)},
                 {"stopped_by", r.stopped_by},   {"samples", r.steps.size()},
                 {"distance_m", r.distance_m},   {"mission_s", r.mission_s},
                 {"spinup_s", r.spinup_s}};
  if (!is_tracker(r.method)) {
    j["median_step_s"] = r.median_step_s();
    j["max_entropy"] = r.max_entropy;
  }
  if (!steps) return j;
  ordered_json s = ordered_json::array();
  for (const TunnelStep& t : r.steps) {
    ordered_json one{{"position", point_json(t.position)},
                     {"gas", t.gas},
                     {"time_s", t.time_s},
                     {"distance_m", t.distance_m},
                     {"phase", t.phase}};
    if (!is_tracker(r.method)) {
      one["estimate"] = point_json(t.estimate);
      one["entropy"] = t.entropy;
      one["compute_s"] = t.compute_s;
    }
    s.push_back(one);
  }
  j["steps"] = s;
  return j;
}

std::string tunnel_runs_csv(const std::vector<TunnelRun>& runs) {
  std::ostringstream out;
  out.precision(6);
  out << "run,method,source_x,source_y,source_z,start_x,start_y,start_z,estimate_x,estimate_y,"
         "estimate_z,error_x,error_y,error_z,error_m,samples,distance_m,mission_s,stopped_by,"
         "success,closest_m,time_within_0_5m_s,median_step_s\n";
  for (std::size_t k = 0; k < runs.size(); ++k) {
    const TunnelRun& r = runs[k];
    const Vec3 e = r.error();
    out << k << ',' << csv_field(r.method) << ',' << r.source.x << ',' << r.source.y << ','
        << r.source.z << ',' << r.start.x << ',' << r.start.y << ',' << r.start.z << ','
        << r.estimate.x << ',' << r.estimate.y << ',' << r.estimate.z << ',' << e.x << ',' << e.y
        << ',' << e.z << ',' << r.error_m() << ',' << r.steps.size() << ',' << r.distance_m << ','
        << r.mission_s << ',' << csv_field(r.stopped_by) << ',' << (succeeded(r) ? 1 : 0) << ','
        << r.closest_m() << ',' << r.time_within(0.5) << ',' << r.median_step_s() << '\n';
  }
  return out.str();
}

ordered_json tunnel_summary(const std::vector<TunnelRun>& runs) {
  std::vector<double> ex, ey, ez, e, dist, time, samples, step;
  for (const TunnelRun& r : runs) {
    const Vec3 v = r.error();
    ex.push_back(v.x), ey.push_back(v.y), ez.push_back(v.z), e.push_back(r.error_m());
    dist.push_back(r.distance_m), time.push_back(r.mission_s);
    samples.push_back(static_cast<double>(r.steps.size()));
    if (!is_tracker(r.method)) step.push_back(r.median_step_s());
  }
  ordered_json j{
      {"runs", runs.size()},
      {"median_error_m", median(e)},
      {"median_error_x_m", median(ex)},
      {"median_error_y_m", median(ey)},
      {"median_error_z_m", median(ez)},
      {"p90_error_z_m", percentile(ez, 0.9)},
      {"success", share(runs, succeeded)},
      {"came_within_0_5m", share(runs, [](const TunnelRun& r) { return r.closest_m() <= 0.5; })},
      {"median_distance_m", median(dist)},
      {"median_mission_s", median(time)},
      {"median_samples", median(samples)}};
  if (!runs.empty() && is_tracker(runs.front().method)) {
    std::vector<double> found_time;
    for (const TunnelRun& r : runs)
      if (r.found()) found_time.push_back(r.mission_s);
    j["median_time_found_s"] = median(found_time);
    std::vector<double> near_time;
    for (const TunnelRun& r : runs)
      if (const double t = r.time_within(0.5); t >= 0.0) near_time.push_back(t);
    j["median_time_within_0_5m_s"] = median(near_time);
  } else {
    j["entropy_stops"] = share(runs, [](const TunnelRun& r) { return r.stopped_by == "entropy"; });
    j["median_step_s"] = median(step);
  }
  return j;
}

std::string tunnel_run_line(const TunnelRun& r) {
  const Vec3 e = r.error();
  std::string s = r.method + ": ";
  if (is_tracker(r.method))
    s += std::string(r.found() ? "found the source" : "did not find the source") + " (ended " +
         fixed(r.error_m(), 2) + " m from it)";
  else
    s += "error " + fixed(r.error_m(), 2) + " m (x " + fixed(e.x, 2) + ", y " + fixed(e.y, 2) +
         ", z " + fixed(e.z, 2) + ")";
  return s + ", " + std::to_string(r.steps.size()) +
         (is_tracker(r.method) ? " decisions, " : " samples, ") + fixed(r.distance_m, 1) + " m, " +
         fixed(r.mission_s, 0) + " s, stopped by " + r.stopped_by;
}

namespace {

// What the run's picture shows, for its legend.
std::string tunnel_run_legend(const TunnelRun& r) {
  std::string legend = "red: source, cyan: start, magenta cross: ";
  legend +=
      is_tracker(r.method)
          ? "end; path blue: Levy walk, green: surge, orange: " +
                std::string(methods::find_tunnel_method(r.method).flies_flat ? "cast" : "spiral")
          : "estimate; dots: samples";
  return legend;
}

// One panel of the run's picture in box b, at ppm pixels per metre: the tunnel from above (x, y)
// or from the side (x, z), with the run's path, its start, the source and the estimate.
void draw_tunnel_panel(cv::Mat& img, TextPainter& text, const cv::Rect& b, bool above,
                       const TunnelRun& r, double ppm) {
  const auto at = [&](Vec3 p) {
    const double v = above ? p.y : p.z;
    return cv::Point(b.x + static_cast<int>(std::lround(p.x * ppm)),
                     b.y + b.height - static_cast<int>(std::lround(v * ppm)));
  };
  cv::rectangle(img, b, cv::Scalar(120, 120, 120), 1);
  text.put(img, above ? "from above (x, y)" : "from the side (x, z)", {b.x, b.y - 20});
  // The wind's direction: the inlet on the left.
  cv::line(img, {b.x - 2, b.y}, {b.x - 2, b.y + b.height}, colours::kInlet, 3);
  for (std::size_t s = 1; s < r.steps.size(); ++s)
    cv::line(img, at(r.steps[s - 1].position), at(r.steps[s].position),
             phase_colour(r.steps[s].phase), 2, cv::LINE_AA);
  if (!is_tracker(r.method))
    for (const TunnelStep& s : r.steps)
      cv::circle(img, at(s.position), 3, colours::kPath, cv::FILLED, cv::LINE_AA);
  cv::circle(img, at(r.start), 6, colours::kStart, cv::FILLED, cv::LINE_AA);
  cv::circle(img, at(r.source), 6, colours::kSource, cv::FILLED, cv::LINE_AA);
  const cv::Point e = at(r.estimate);
  cv::drawMarker(img, e, colours::kEstimate, cv::MARKER_CROSS, 14, 2, cv::LINE_AA);
  draw_metre_axes(img, text, b, ppm, {0.0, 0.0}, "x [m]", above ? "y [m]" : "z [m]");
}

}  // namespace

Picture draw_tunnel_run(const TunnelRun& r, const world::Tunnel& t, const std::string& title) {
  // 60 px per metre, two panels: (x, y) above, (x, z) below, y and z upwards, each with axes in
  // metres (the maps' axes, map/map_render.hpp).
  const double ppm = std::min(60.0, 1200.0 / t.length);
  const int w = static_cast<int>(std::lround(t.length * ppm));
  const int h1 = static_cast<int>(std::lround(t.width * ppm));
  const int h2 = static_cast<int>(std::lround(t.height * ppm));
  TextPainter text(0.5, 1);
  const AxesMargins m1 = metre_axes_margins(text, {0, 0, w, h1}, ppm, {0.0, 0.0});
  const AxesMargins m2 = metre_axes_margins(text, {0, 0, w, h2}, ppm, {0.0, 0.0});
  const int left = std::max(50, std::max(m1.left, m2.left) + 6);
  const int gap = m1.bottom + 30;  // the upper panel's axes, then the lower one's name
  const int width = std::max(left + w + 30, 640);
  // The title wrapped to the picture's width, above the panels.
  const std::vector<std::string> lines = wrap_words(text, title, width - 20, text.scale());
  const int line_h = text.size("Ag").height + 6;
  const int top = 10 + static_cast<int>(lines.size()) * line_h + 30;
  // The legend, wrapped likewise, below the panels.
  const std::vector<std::string> legend_lines =
      wrap_words(text, tunnel_run_legend(r), width - left - 10, text.scale());
  const int legend_y = top + h1 + gap + h2 + m2.bottom + 10;
  cv::Mat img(legend_y + static_cast<int>(legend_lines.size()) * line_h + 10, width, CV_8UC3,
              cv::Scalar(255, 255, 255));
  for (std::size_t k = 0; k < lines.size(); ++k)
    text.put(img, lines[k], {10, 8 + static_cast<int>(k) * line_h});
  const cv::Rect panels[2] = {{left, top, w, h1}, {left, top + h1 + gap, w, h2}};
  for (int k = 0; k < 2; ++k)
    draw_tunnel_panel(img, text, panels[k], k == 0, r, ppm);
  for (std::size_t k = 0; k < legend_lines.size(); ++k)
    text.put(img, legend_lines[k], {left, legend_y + static_cast<int>(k) * line_h});
  Picture p;
  p.image = img;
  p.text_boxes = text.boxes();
  p.arena = panels[0];
  return p;
}

Picture draw_tunnel_box_plot(const std::vector<TunnelRun>& runs, const std::string& title) {
  if (!runs.empty() && is_tracker(runs.front().method)) {
    std::vector<double> found, all;
    for (const TunnelRun& r : runs) {
      all.push_back(r.mission_s);
      if (r.found()) found.push_back(r.mission_s);
    }
    BoxPlot plot;
    plot.groups = {found, all};
    plot.names = {"found", "all runs"};
    plot.title = title;
    plot.y_label = "mission time, s";
    plot.x_label = "runs";
    return draw_box_plot(plot);
  }
  std::vector<std::vector<double>> e(3);
  for (const TunnelRun& r : runs) {
    const Vec3 v = r.error();
    e[0].push_back(v.x), e[1].push_back(v.y), e[2].push_back(v.z);
  }
  BoxPlot plot;
  plot.groups = e;
  plot.names = {"x", "y", "z"};
  plot.title = title;
  plot.y_label = "error, m";
  plot.x_label = "axis";
  return draw_box_plot(plot);
}

}  // namespace plumekit::run
