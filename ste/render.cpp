#include "ste/render.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include <opencv2/imgproc.hpp>

#include "core/map_render.hpp"

namespace plumekit::ste {

namespace {

const cv::Scalar kPath(235, 235, 235), kStart(40, 170, 40), kEstimate(200, 40, 200);

cv::Scalar colour_of(double v, double lo, double hi, int colormap) {
  const double t = hi > lo ? std::clamp((v - lo) / (hi - lo), 0.0, 1.0) : 0.0;
  cv::Mat grey(1, 1, CV_8U, cv::Scalar(static_cast<int>(std::lround(255 * t)))), bgr;
  cv::applyColorMap(grey, bgr, colormap);
  const cv::Vec3b c = bgr.at<cv::Vec3b>(0, 0);
  return {static_cast<double>(c[0]), static_cast<double>(c[1]), static_cast<double>(c[2])};
}

void draw_cross(MapCanvas& canvas, Vec2 p, const cv::Scalar& colour) {
  const cv::Point c = canvas.pixel(p);
  const int r = 8;
  for (int t : {5, 2}) {
    const cv::Scalar col = t == 5 ? cv::Scalar(255, 255, 255) : colour;
    cv::line(canvas.image(), c + cv::Point(-r, -r), c + cv::Point(r, r), col, t, cv::LINE_AA);
    cv::line(canvas.image(), c + cv::Point(-r, r), c + cv::Point(r, -r), col, t, cv::LINE_AA);
  }
}

Map with_source(const Map& map, Vec2 source) {
  Map m = map;
  m.sources = {source};
  return m;
}

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const double pos = q * (v.size() - 1);
  const std::size_t i = static_cast<std::size_t>(pos);
  const double f = pos - i;
  return i + 1 < v.size() ? v[i] * (1 - f) + v[i + 1] * f : v[i];
}

std::string fmt(double v, int digits = 2) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(digits) << v;
  return s.str();
}

}  // namespace

cv::Mat draw_trajectory(const Map& map, const Grid<double>& mean_plume,
                        const LocalizationResult& run, Vec2 source, const std::string& title) {
  MapCanvas canvas(with_source(map, source));
  canvas.draw_free_space();
  // Colour scale: the plume up to its 99th percentile, so one hot cell at the
  // source does not wash the rest out; samples share it.
  std::vector<double> v;
  for (double c : mean_plume.values)
    if (c > 0.0) v.push_back(c);
  double hi = std::max(1.0, percentile(v, 0.99));
  const int cmap = cv::COLORMAP_VIRIDIS;
  canvas.draw_field(mean_plume, 0.0, hi, cmap);
  canvas.draw_obstacles();
  canvas.draw_walls_and_openings();
  canvas.draw_axes_and_scale();
  for (const Step& s : run.steps)
    if (!s.path_in.empty()) canvas.draw_path(s.path_in, kPath, 2);
  canvas.draw_sources();
  canvas.draw_marker(run.start, kStart, 7);
  for (const Step& s : run.steps)
    canvas.draw_marker(s.position, colour_of(s.value, 0.0, hi, cmap), 5);
  draw_cross(canvas, run.estimate, kEstimate);
  canvas.draw_colour_bar(0.0, hi, "mean concentration", cmap);
  canvas.draw_title(title);
  return canvas.image().clone();
}

cv::Mat draw_posterior(const Map& map, const Posterior& posterior, Vec2 source, Vec2 estimate,
                       const std::string& title) {
  MapCanvas canvas(with_source(map, source));
  canvas.draw_free_space();
  // log10 of the probability relative to the most probable cell, over six
  // decades: a certain posterior is one cell, and its tails still show.
  Grid<double> field = posterior.marginal;
  const double top = *std::max_element(field.values.begin(), field.values.end());
  for (double& d : field.values)
    d = d > 0.0 && top > 0.0 ? std::max(-6.0, std::log10(d / top)) : -6.0;
  canvas.draw_field(field, -6.0, 0.0, cv::COLORMAP_INFERNO);
  canvas.draw_obstacles();
  canvas.draw_walls_and_openings();
  canvas.draw_axes_and_scale();
  canvas.draw_sources();
  draw_cross(canvas, estimate, kEstimate);
  canvas.draw_colour_bar(-6.0, 0.0, "log10 P / max P", cv::COLORMAP_INFERNO);
  canvas.draw_title(title);
  return canvas.image().clone();
}

cv::Mat draw_box_plot(const std::vector<std::vector<double>>& groups,
                      const std::vector<std::string>& labels, const std::string& y_label,
                      const std::string& title, double reference_line) {
  const int w_box = 70, left = 80, right = 30, top = 50, bottom = 70, height = 360;
  const int width =
      left + right + w_box * static_cast<int>(std::max<std::size_t>(1, groups.size()));
  cv::Mat img(top + height + bottom, width, CV_8UC3, cv::Scalar(255, 255, 255));
  double ymax = reference_line > 0.0 ? reference_line * 1.2 : 0.0;
  for (const auto& g : groups)
    for (double v : g)
      ymax = std::max(ymax, v);
  ymax = ymax > 0.0 ? ymax * 1.05 : 1.0;
  auto y_px = [&](double v) {
    return top + height - static_cast<int>(std::lround(v / ymax * height));
  };
  const cv::Scalar ink(40, 40, 40), grid(225, 225, 225), box(200, 120, 40);
  // Axis, ticks and grid lines.
  double step = std::pow(10.0, std::floor(std::log10(ymax)));
  if (ymax / step < 3) step /= 2;
  for (double t = 0.0; t <= ymax + 1e-12; t += step) {
    cv::line(img, {left, y_px(t)}, {width - right, y_px(t)}, grid, 1);
    cv::putText(img, fmt(t, step < 1 ? 2 : 0), {8, y_px(t) + 4}, cv::FONT_HERSHEY_SIMPLEX, 0.4, ink,
                1, cv::LINE_AA);
  }
  if (reference_line > 0.0)
    cv::line(img, {left, y_px(reference_line)}, {width - right, y_px(reference_line)},
             cv::Scalar(60, 60, 220), 1, cv::LINE_AA);
  cv::line(img, {left, top}, {left, top + height}, ink, 1);
  cv::line(img, {left, top + height}, {width - right, top + height}, ink, 1);
  cv::putText(img, title, {left, 28}, cv::FONT_HERSHEY_SIMPLEX, 0.55, ink, 1, cv::LINE_AA);
  cv::putText(img, y_label, {8, top - 8}, cv::FONT_HERSHEY_SIMPLEX, 0.42, ink, 1, cv::LINE_AA);
  cv::putText(img, "test map", {(left + width - right) / 2 - 30, top + height + 45},
              cv::FONT_HERSHEY_SIMPLEX, 0.45, ink, 1, cv::LINE_AA);
  for (std::size_t k = 0; k < groups.size(); ++k) {
    const int cx = left + w_box * static_cast<int>(k) + w_box / 2;
    const std::string& label = k < labels.size() ? labels[k] : std::to_string(k);
    cv::putText(img, label, {cx - 4 * static_cast<int>(label.size()), top + height + 18},
                cv::FONT_HERSHEY_SIMPLEX, 0.4, ink, 1, cv::LINE_AA);
    if (groups[k].empty()) continue;
    const double q1 = percentile(groups[k], 0.25), q2 = percentile(groups[k], 0.5),
                 q3 = percentile(groups[k], 0.75), iqr = q3 - q1;
    double lo = q3, hi = q1;
    for (double v : groups[k]) {
      if (v >= q1 - 1.5 * iqr) lo = std::min(lo, v);
      if (v <= q3 + 1.5 * iqr) hi = std::max(hi, v);
    }
    const int half = w_box / 4;
    cv::line(img, {cx, y_px(lo)}, {cx, y_px(q1)}, ink, 1);
    cv::line(img, {cx, y_px(q3)}, {cx, y_px(hi)}, ink, 1);
    cv::line(img, {cx - half / 2, y_px(lo)}, {cx + half / 2, y_px(lo)}, ink, 1);
    cv::line(img, {cx - half / 2, y_px(hi)}, {cx + half / 2, y_px(hi)}, ink, 1);
    cv::rectangle(img, {cx - half, y_px(q3)}, {cx + half, y_px(q1)}, box, cv::FILLED);
    cv::rectangle(img, {cx - half, y_px(q3)}, {cx + half, y_px(q1)}, ink, 1);
    cv::line(img, {cx - half, y_px(q2)}, {cx + half, y_px(q2)}, cv::Scalar(30, 30, 200), 2);
    for (double v : groups[k])
      if (v < lo || v > hi) cv::circle(img, {cx, y_px(v)}, 3, ink, 1, cv::LINE_AA);
  }
  return img;
}

}  // namespace plumekit::ste
