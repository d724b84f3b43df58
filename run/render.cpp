#include "run/render.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <iomanip>
#include <sstream>

#include <opencv2/imgproc.hpp>

#include "core/statistics.hpp"

namespace plumekit::run {

namespace {

const cv::Scalar kTrack(235, 235, 235);
// A team's robots (BGR): white first, as a robot alone, then colours that read on viridis.
const cv::Scalar kRobotTracks[] = {{235, 235, 235}, {60, 140, 255}, {255, 200, 60},
                                   {200, 80, 255},  {90, 90, 255},  {120, 255, 160}};
cv::Scalar robot_track(std::size_t k) {
  return kRobotTracks[k % (sizeof(kRobotTracks) / sizeof(kRobotTracks[0]))];
}

cv::Scalar colour_of(double v, double lo, double hi, int colormap) {
  const double t = hi > lo ? std::clamp((v - lo) / (hi - lo), 0.0, 1.0) : 0.0;
  cv::Mat grey(1, 1, CV_8U, cv::Scalar(static_cast<int>(std::lround(255 * t)))), bgr;
  cv::applyColorMap(grey, bgr, colormap);
  const cv::Vec3b c = bgr.at<cv::Vec3b>(0, 0);
  return {static_cast<double>(c[0]), static_cast<double>(c[1]), static_cast<double>(c[2])};
}

Map with_source(const Map& map, Vec2 source) {
  Map m = map;
  m.sources = {source};
  return m;
}

std::string fmt(double v, int digits = 2) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(digits) << v;
  return s.str();
}

std::string source_label(const RunToDraw& run) {
  return run.source_index >= 0 ? "S" + std::to_string(run.source_index) : "source";
}

// "<map>: <model>, source S1 run 3", the part every picture of a run shares.
std::string run_heading(const Map& map, const RunToDraw& run) {
  const Vec2 source = map.to_frame(run.source);  // what the user typed: the map's frame
  std::string s = (map.name.empty() ? "map" : map.name) + ": " + run.model + ", source " +
                  (run.source_index >= 0 ? source_label(run)
                                         : "(" + fmt(source.x) + ", " + fmt(source.y) + ")");
  if (run.run >= 0) s += " run " + std::to_string(run.run);
  return s;
}

std::vector<LegendEntry> run_legend() {
  return {{LegendEntry::Symbol::Ring, colours::kStart, "start"},
          {LegendEntry::Symbol::Cross, colours::kEstimate, "estimate"}};
}

}  // namespace

RunToDraw run_to_draw(const RunRecord& record, const std::string& model,
                      const std::string& chosen_as) {
  return {&record.result, record.source, record.source_index, record.run, model, chosen_as};
}

RunToDraw run_to_draw(const Map& map, const LocalizationResult& result, Vec2 source,
                      const std::string& model) {
  int index = -1;
  for (std::size_t k = 0; k < map.sources.size(); ++k)
    if (norm(map.sources[k] - source) < 1e-9) index = static_cast<int>(k);
  return {&result, source, index, -1, model, ""};
}

std::string trajectory_title(const Map& map, const RunToDraw& run) {
  const LocalizationResult& r = *run.result;
  std::string title = run_heading(map, run) + ": error " + fmt(norm(r.estimate - run.source)) +
                      " m, " + std::to_string(r.samples) + " samples, " + fmt(r.distance_m, 1) +
                      " m travelled, stopped by " + r.stopped_by;
  if (!r.team.empty())
    title += "; " + std::to_string(r.team.size()) + " " + r.strategy + " robots, robot " +
             std::to_string(r.declared_by + 1) + "'s estimate";
  if (!run.chosen_as.empty()) title += " (" + run.chosen_as + ")";
  return title;
}

Picture draw_trajectory(const Map& map, const Grid<double>& mean_plume, const RunToDraw& run,
                        const RenderOptions& options) {
  const LocalizationResult& r = *run.result;
  // Colour scale: the plume up to its 99th percentile, so one hot cell at the
  // source does not wash the rest out; samples share it.
  std::vector<double> v;
  for (double c : mean_plume.values)
    if (c > 0.0) v.push_back(c);
  const double hi = std::max(1.0, percentile(v, 0.99));
  const int cmap = cv::COLORMAP_VIRIDIS;
  const std::string title = trajectory_title(map, run);
  // Every robot's start and stops; a robot alone is a team of one.
  struct Track {
    Vec2 start;
    const std::vector<Step>* steps;
  };
  std::vector<Track> robots;
  for (const TeamRobot& t : r.team)
    robots.push_back({t.start, &t.steps});
  if (robots.empty()) robots.push_back({r.start, &r.steps});
  std::vector<LegendEntry> legend;
  for (std::size_t k = 0; k < robots.size(); ++k)
    if (robots.size() == 1)
      legend.push_back({LegendEntry::Symbol::Line, kTrack, "path"});
    else if (k < 6)
      legend.push_back({LegendEntry::Symbol::Line, robot_track(k),
                        "robot " + std::to_string(k + 1) +
                            (static_cast<int>(k) == r.declared_by ? " (its estimate)" : "")});
  legend.push_back(
      {LegendEntry::Symbol::Dot, colour_of(hi, 0, hi, cmap), "sample (coloured by its reading)"});
  for (const LegendEntry& e : run_legend())
    legend.push_back(e);
  Frame frame{title, ColourBar{0.0, hi, "mean [concentration units]", cmap}, legend, true};
  MapCanvas canvas(with_source(map, run.source), options, frame);
  canvas.draw_free_space();
  canvas.draw_field(mean_plume, 0.0, hi, cmap);
  canvas.draw_obstacles();
  canvas.draw_walls_and_openings();
  for (std::size_t k = 0; k < robots.size(); ++k)
    for (const Step& s : *robots[k].steps)
      if (!s.path_in.empty()) canvas.draw_path(s.path_in, robot_track(k), 2);
  if (r.approach.size() >= 2) canvas.draw_path(r.approach, robot_track(0), 2);
  canvas.draw_source(run.source, source_label(run));
  // Samples on the plume's colour scale with a thin grey rim (no white halo, so a
  // low reading shows the colour map's dark end, as the plume under it does); a team's have
  // their robot's colour as the rim.
  const int radius = static_cast<int>(std::lround(6 * canvas.mark_scale()));
  for (std::size_t k = 0; k < robots.size(); ++k)
    for (const Step& s : *robots[k].steps) {
      cv::circle(canvas.image(), canvas.pixel(s.position), radius,
                 colour_of(s.value, 0.0, hi, cmap), cv::FILLED, cv::LINE_AA);
      cv::circle(canvas.image(), canvas.pixel(s.position), radius,
                 robots.size() == 1 ? cv::Scalar(150, 150, 150) : robot_track(k),
                 robots.size() == 1 ? 1 : 2, cv::LINE_AA);
    }
  // The starts as rings, around the first samples that are usually taken there.
  for (const Track& robot : robots)
    canvas.draw_ring(robot.start, colours::kStart, 11);
  canvas.draw_cross(r.estimate, colours::kEstimate);
  return canvas.finish();
}

Picture draw_posterior(const Map& map, const RunToDraw& run, const RenderOptions& options) {
  const LocalizationResult& r = *run.result;
  // log10 of the probability relative to the most probable cell, over six
  // decades: a certain posterior is one cell, and its tails still show.
  Grid<double> field = r.posterior.marginal;
  const double top = *std::max_element(field.values.begin(), field.values.end());
  for (double& d : field.values)
    d = d > 0.0 && top > 0.0 ? std::max(-6.0, std::log10(d / top)) : -6.0;
  Frame frame{run_heading(map, run) + ": final posterior, error " +
                  fmt(norm(r.estimate - run.source)) + " m",
              ColourBar{-6.0, 0.0, "log10 P / max P [-]", cv::COLORMAP_INFERNO},
              {{LegendEntry::Symbol::Cross, colours::kEstimate, "estimate"}},
              true};
  MapCanvas canvas(with_source(map, run.source), options, frame);
  canvas.draw_free_space();
  canvas.draw_field(field, -6.0, 0.0, cv::COLORMAP_INFERNO);
  canvas.draw_obstacles();
  canvas.draw_walls_and_openings();
  canvas.draw_source(run.source, source_label(run));
  canvas.draw_cross(r.estimate, colours::kEstimate);
  return canvas.finish();
}

namespace {

// The box plot's geometry, from its measured text.
struct BoxLayout {
  int text_h, gap, tick, left, top, plot_h, col_w, width, height;
  double ymax, step;
  std::vector<std::string> title_lines;
  LegendLayout legend;
};

const cv::Scalar kInk(40, 40, 40), kGridLine(225, 225, 225), kBox(200, 120, 40),
    kMedian(30, 30, 200), kReference(60, 60, 220);
constexpr int kPlotHeight = 360;

std::vector<LegendEntry> box_legend(const BoxPlot& p) {
  std::vector<LegendEntry> l{{LegendEntry::Symbol::Swatch, kBox, "quartiles"},
                             {LegendEntry::Symbol::Line, kMedian, "median"},
                             {LegendEntry::Symbol::Line, kInk, "whiskers: 1.5 IQR"},
                             {LegendEntry::Symbol::Ring, kInk, "outlier"}};
  if (p.reference > 0.0)
    l.push_back({LegendEntry::Symbol::Line, kReference,
                 p.reference_label.empty() ? "reference " + fmt(p.reference) : p.reference_label});
  return l;
}

std::string count_label(const std::vector<double>& g) {
  return "n = " + std::to_string(g.size());
}

double tick_step(double ymax) {
  double step = std::pow(10.0, std::floor(std::log10(ymax)));
  if (ymax / step < 3) step /= 2;
  return step;
}

std::string tick_text(double t, double step) {
  return fmt(t, step < 1 ? 2 : 0);
}

BoxLayout plan_box_plot(const BoxPlot& p, const TextPainter& text) {
  BoxLayout l{};
  l.text_h = text.size("Ag").height;
  l.gap = std::max(4, l.text_h / 2);
  l.tick = 4;
  l.ymax = p.reference > 0.0 ? p.reference * 1.2 : 0.0;
  for (const auto& g : p.groups)
    for (double v : g)
      l.ymax = std::max(l.ymax, v);
  l.ymax = l.ymax > 0.0 ? l.ymax * 1.05 : 1.0;
  l.step = tick_step(l.ymax);
  int tick_w = 0;
  for (double t = 0.0; t <= l.ymax + 1e-12; t += l.step)
    tick_w = std::max(tick_w, text.size(tick_text(t, l.step)).width);
  l.left = l.gap + l.text_h + l.gap + tick_w + l.gap / 2 + l.tick;
  // A column holds its name and its count, with room either side.
  l.col_w = 70;
  for (std::size_t k = 0; k < p.groups.size(); ++k) {
    const std::string name = k < p.names.size() ? p.names[k] : std::to_string(k);
    l.col_w = std::max({l.col_w, text.size(name).width + 2 * l.gap,
                        text.size(count_label(p.groups[k])).width + 2 * l.gap});
  }
  const int n = static_cast<int>(std::max<std::size_t>(1, p.groups.size()));
  l.plot_h = std::max(kPlotHeight, text.size(p.y_label).width + 2 * l.gap);
  l.width = l.left + n * l.col_w + 2 * l.gap;
  const double title_scale = text.scale() * 1.2;
  l.width = std::max(l.width, text.size(p.x_label).width + 2 * l.gap);
  std::istringstream words(p.title);
  for (std::string w; words >> w;)
    l.width = std::max(l.width, text.size(w, title_scale).width + 2 * l.gap);
  const std::vector<LegendEntry> legend = box_legend(p);
  l.width = std::max(l.width, plan_legend(text, legend, l.width).widest + 2 * l.gap);
  l.legend = plan_legend(text, legend, l.width);
  l.title_lines = wrap_words(text, p.title, l.width - 2 * l.gap, title_scale);
  const int title_h = text.size("Ag", title_scale).height;
  l.top =
      l.gap + static_cast<int>(l.title_lines.size()) * (title_h + l.gap / 2) + l.gap + l.text_h / 2;
  const int below =
      l.tick + l.gap / 2 + 2 * l.text_h + l.gap + l.text_h + l.gap + l.legend.height() + l.gap;
  l.height = l.top + l.plot_h + below;
  return l;
}

void draw_box(cv::Mat& img, const std::vector<double>& g, int cx, int half,
              const std::function<int(double)>& y_px) {
  const double q1 = percentile(g, 0.25), q2 = percentile(g, 0.5), q3 = percentile(g, 0.75),
               iqr = q3 - q1;
  double lo = q3, hi = q1;
  for (double v : g) {
    if (v >= q1 - 1.5 * iqr) lo = std::min(lo, v);
    if (v <= q3 + 1.5 * iqr) hi = std::max(hi, v);
  }
  cv::line(img, {cx, y_px(lo)}, {cx, y_px(q1)}, kInk, 1);
  cv::line(img, {cx, y_px(q3)}, {cx, y_px(hi)}, kInk, 1);
  cv::line(img, {cx - half / 2, y_px(lo)}, {cx + half / 2, y_px(lo)}, kInk, 1);
  cv::line(img, {cx - half / 2, y_px(hi)}, {cx + half / 2, y_px(hi)}, kInk, 1);
  cv::rectangle(img, {cx - half, y_px(q3)}, {cx + half, y_px(q1)}, kBox, cv::FILLED);
  cv::rectangle(img, {cx - half, y_px(q3)}, {cx + half, y_px(q1)}, kInk, 1);
  cv::line(img, {cx - half, y_px(q2)}, {cx + half, y_px(q2)}, kMedian, 2);
  for (double v : g)
    if (v < lo || v > hi) cv::circle(img, {cx, y_px(v)}, 4, kInk, 2, cv::LINE_AA);
}

}  // namespace

Picture draw_box_plot(const BoxPlot& p) {
  TextPainter text(0.45, 1);
  const BoxLayout l = plan_box_plot(p, text);
  cv::Mat img(l.height, l.width, CV_8UC3, cv::Scalar(255, 255, 255));
  const int right = l.left + static_cast<int>(std::max<std::size_t>(1, p.groups.size())) * l.col_w;
  const int bottom = l.top + l.plot_h;
  auto y_px = [&](double v) {
    return bottom - static_cast<int>(std::lround(v / l.ymax * l.plot_h));
  };
  for (double t = 0.0; t <= l.ymax + 1e-12; t += l.step) {
    cv::line(img, {l.left, y_px(t)}, {right, y_px(t)}, kGridLine, 1);
    cv::line(img, {l.left - l.tick, y_px(t)}, {l.left, y_px(t)}, kInk, 1);
    const std::string s = tick_text(t, l.step);
    text.put(img, s, {l.left - l.tick - l.gap / 2 - text.size(s).width, y_px(t) - l.text_h / 2});
  }
  if (p.reference > 0.0)
    cv::line(img, {l.left, y_px(p.reference)}, {right, y_px(p.reference)}, kReference, 1,
             cv::LINE_AA);
  cv::line(img, {l.left, l.top}, {l.left, bottom}, kInk, 1);
  cv::line(img, {l.left, bottom}, {right, bottom}, kInk, 1);
  text.put_vertical(img, p.y_label, {l.gap, l.top + l.plot_h / 2 - text.size(p.y_label).width / 2});
  for (std::size_t k = 0; k < p.groups.size(); ++k) {
    const int cx = l.left + l.col_w * static_cast<int>(k) + l.col_w / 2;
    const std::string name = k < p.names.size() ? p.names[k] : std::to_string(k);
    const std::string count = count_label(p.groups[k]);
    const int y = bottom + l.tick + l.gap / 2;
    text.put(img, name, {cx - text.size(name).width / 2, y});
    text.put(img, count, {cx - text.size(count).width / 2, y + l.text_h});
    if (!p.groups[k].empty()) draw_box(img, p.groups[k], cx, std::min(18, l.col_w / 4), y_px);
  }
  int y = bottom + l.tick + l.gap / 2 + 2 * l.text_h + l.gap;
  text.put(img, p.x_label,
           {std::max(l.gap, (l.left + right) / 2 - text.size(p.x_label).width / 2), y});
  y += l.text_h + l.gap;
  draw_legend(img, text, box_legend(p), l.legend, {l.gap, y});
  int ty = l.gap;
  for (const std::string& line : l.title_lines) {
    text.put(img, line, {l.gap, ty}, text.scale() * 1.2);
    ty += text.size("Ag", text.scale() * 1.2).height + l.gap / 2;
  }
  return {img, text.boxes(), cv::Rect()};
}

Picture draw_box_plot(const std::vector<std::vector<double>>& groups,
                      const std::vector<std::string>& names, const std::string& y_label,
                      const std::string& title, double reference_line) {
  BoxPlot p;
  p.groups = groups;
  p.names = names;
  p.y_label = y_label;
  p.title = title;
  p.reference = reference_line;
  if (reference_line > 0.0) p.reference_label = "success radius " + fmt(reference_line) + " m";
  return draw_box_plot(p);
}

}  // namespace plumekit::run
