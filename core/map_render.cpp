#include "core/map_render.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/image_io.hpp"
#include "core/memory_limit.hpp"
#include "core/option_check.hpp"
#include "core/output_target.hpp"

namespace plumekit {

namespace {

// Colours are BGR.
const cv::Scalar kBackground(255, 255, 255);
const cv::Scalar kFreeSpace(248, 246, 244);
const cv::Scalar kObstacle(105, 100, 95);
const cv::Scalar kWall(20, 20, 20);
const cv::Scalar kInlet(200, 110, 20);
const cv::Scalar kOutlet(40, 150, 40);
const cv::Scalar kSource(30, 30, 220);
const cv::Scalar kText(30, 30, 30);

constexpr int kShift = 4;  // fractional bits for sub-pixel drawing
constexpr double kScale = 1 << kShift;
constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;

cv::Point fixed(cv::Point2d p) {
  return {static_cast<int>(std::lround(p.x * kScale)), static_cast<int>(std::lround(p.y * kScale))};
}

std::string format_number(double x) {
  std::ostringstream s;
  s << std::setprecision(3) << x;
  return s.str();
}

void put_text(cv::Mat& img, const std::string& text, cv::Point at, double size,
              const cv::Scalar& colour, bool centred = false) {
  int baseline = 0;
  const cv::Size box = cv::getTextSize(text, kFont, size, 1, &baseline);
  if (centred) at.x -= box.width / 2;
  cv::putText(img, text, at, kFont, size, colour, 1, cv::LINE_AA);
}

}  // namespace

namespace {

// Margins around the arena, pixels.
constexpr int kLeft = 56, kTop = 40, kRight = 110, kBottom = 76;
// Longest side a picture may have: OpenCV draws in int pixel coordinates with
// 4 fractional bits, and no screen or page needs more.
constexpr double kMaxSidePx = 30000.0;
// Bytes per pixel at the peak: the BGR image, a tinted copy and the blend
// (map render --cells), and the PNG's rows.
constexpr double kBytesPerPixel = 4 * 3.0;

// The picture's size in pixels, checked: px_per_m in range, each side within
// kMaxSidePx, its memory within the limit (core/memory_limit.hpp).
cv::Size checked_size(const Map& map, double px_per_m) {
  check_positive("render.px_per_m", px_per_m, 1000.0, "pixels per metre", "the default is 100");
  const double w = std::ceil(map.width * px_per_m) + kLeft + kRight;
  const double h = std::ceil(map.height * px_per_m) + kTop + kBottom;
  // The largest px_per_m whose picture meets both bounds, for the advice.
  const double side = std::max(map.width, map.height);
  double fit = (kMaxSidePx - kLeft - kRight) / side;
  fit = std::min(fit, std::sqrt(memory_limit() / kBytesPerPixel / (map.width * map.height)));
  const std::string advice =
      "use a smaller render.px_per_m (" + compact(std::floor(fit * 100) / 100) + " fits)";
  if (std::max(w, h) > kMaxSidePx)
    throw OptionError("render.px_per_m", compact(px_per_m) + " pixels per metre on the " +
                                             compact(map.width) + " x " + compact(map.height) +
                                             " m arena gives a " + compact(w) + " x " + compact(h) +
                                             " px picture, more than " + compact(kMaxSidePx) +
                                             " px per side; " + advice);
  check_memory(w * h * kBytesPerPixel,
               "a " + compact(w) + " x " + compact(h) + " px picture of the map", advice);
  return {static_cast<int>(w), static_cast<int>(h)};
}

}  // namespace

MapCanvas::MapCanvas(const Map& map, double px_per_m)
    : map_(map), px_per_m_(px_per_m), left_(kLeft), top_(kTop), right_(kRight) {
  image_ = cv::Mat(checked_size(map, px_per_m), CV_8UC3, kBackground);
}

cv::Point2d MapCanvas::to_px(Vec2 p) const {
  return {left_ + p.x * px_per_m_, top_ + (map_.height - p.y) * px_per_m_};
}

cv::Point MapCanvas::pixel(Vec2 p) const {
  const cv::Point2d q = to_px(p);
  return {static_cast<int>(std::lround(q.x)), static_cast<int>(std::lround(q.y))};
}

void MapCanvas::draw_free_space() {
  cv::rectangle(image_, pixel({0, map_.height}), pixel({map_.width, 0}), kFreeSpace, cv::FILLED);
}

void MapCanvas::draw_obstacles() {
  for (const Polygon& poly : map_.obstacles) {
    std::vector<cv::Point> pts;
    for (Vec2 v : poly)
      pts.push_back(fixed(to_px(v)));
    const std::vector<std::vector<cv::Point>> polys{pts};
    cv::fillPoly(image_, polys, kObstacle, cv::LINE_AA, kShift);
    cv::polylines(image_, polys, true, kObstacle * 0.6, 1, cv::LINE_AA, kShift);
  }
}

void MapCanvas::draw_walls_and_openings() {
  const double w = map_.width, h = map_.height;
  cv::rectangle(image_, pixel({0, h}), pixel({w, 0}), kWall, 2, cv::LINE_AA);

  // An opening: a thick coloured band on its wall with arrows across it.
  auto opening = [&](const Opening& o, const cv::Scalar& colour, bool inward) {
    const Vec2 a = map_.wall_point(o.side, o.from), b = map_.wall_point(o.side, o.to);
    cv::line(image_, fixed(to_px(a)), fixed(to_px(b)), colour, 6, cv::LINE_AA, kShift);
    const Vec2 normal = o.side == Side::Left     ? Vec2{1, 0}
                        : o.side == Side::Right  ? Vec2{-1, 0}
                        : o.side == Side::Bottom ? Vec2{0, 1}
                                                 : Vec2{0, -1};
    const double arrow = 28.0 / px_per_m_;  // metres
    const int count = std::max(1, static_cast<int>((o.to - o.from) / (60.0 / px_per_m_)));
    for (int k = 0; k < count; ++k) {
      const Vec2 base = map_.wall_point(o.side, o.from + (k + 0.5) * (o.to - o.from) / count);
      // Inlet arrows point into the arena, outlet arrows out through the wall.
      const Vec2 from = inward ? base : base + arrow * normal;
      const Vec2 to = inward ? base + arrow * normal : base;
      cv::arrowedLine(image_, pixel(from), pixel(to), colour, 2, cv::LINE_AA, 0, 0.35);
    }
  };
  opening(map_.inlet, kInlet, true);
  opening(map_.outlet, kOutlet, false);
}

void MapCanvas::draw_marker(Vec2 p, const cv::Scalar& colour, int radius_px) {
  cv::circle(image_, fixed(to_px(p)), radius_px * static_cast<int>(kScale) + 2 * kScale,
             cv::Scalar(255, 255, 255), cv::FILLED, cv::LINE_AA, kShift);
  cv::circle(image_, fixed(to_px(p)), radius_px * static_cast<int>(kScale), colour, cv::FILLED,
             cv::LINE_AA, kShift);
}

void MapCanvas::draw_sources() {
  for (std::size_t k = 0; k < map_.sources.size(); ++k) {
    draw_marker(map_.sources[k], kSource, 6);
    put_text(image_, "S" + std::to_string(k), pixel(map_.sources[k]) + cv::Point(9, -7), 0.45,
             kSource);
  }
}

void MapCanvas::draw_axes_and_scale() {
  // Metre ticks along the bottom and left walls; a step that keeps labels apart.
  double step = 1.0;
  while (step * px_per_m_ < 40.0)
    step *= 2.0;
  for (double x = 0.0; x <= map_.width + 1e-9; x += step) {
    const cv::Point p = pixel({x, 0});
    cv::line(image_, p, p + cv::Point(0, 6), kText, 1, cv::LINE_AA);
    put_text(image_, format_number(x), p + cv::Point(0, 20), 0.4, kText, true);
  }
  for (double y = 0.0; y <= map_.height + 1e-9; y += step) {
    const cv::Point p = pixel({0, y});
    cv::line(image_, p, p - cv::Point(6, 0), kText, 1, cv::LINE_AA);
    put_text(image_, format_number(y), p + cv::Point(-30, 5), 0.4, kText);
  }
  // A scale bar under the axis: `step` metres long, with its length written on it.
  const cv::Point a = pixel({0, 0}) + cv::Point(0, 44);
  const cv::Point b = a + cv::Point(static_cast<int>(std::lround(step * px_per_m_)), 0);
  cv::line(image_, a, b, kText, 3);
  cv::line(image_, a - cv::Point(0, 5), a + cv::Point(0, 5), kText, 1);
  cv::line(image_, b - cv::Point(0, 5), b + cv::Point(0, 5), kText, 1);
  put_text(image_, format_number(step) + " m", b + cv::Point(8, 5), 0.45, kText);
  put_text(image_, "x [m]", pixel({map_.width, 0}) + cv::Point(-36, 40), 0.4, kText);

  // Legend, right of the scale bar.
  cv::Point at = b + cv::Point(80, 0);
  auto swatch = [&](const cv::Scalar& colour, const std::string& text) {
    cv::rectangle(image_, at + cv::Point(0, -6), at + cv::Point(18, 6), colour, cv::FILLED);
    put_text(image_, text, at + cv::Point(24, 5), 0.45, kText);
    int baseline = 0;
    at.x += 24 + cv::getTextSize(text, kFont, 0.45, 1, &baseline).width + 26;
  };
  swatch(kInlet, "inlet (" + std::string(to_string(map_.inlet.side)) + ", " +
                     format_number(map_.inlet.speed) + " m/s " + to_string(map_.inlet.profile) +
                     ")");
  swatch(kOutlet, "outlet (" + std::string(to_string(map_.outlet.side)) + ")");
  swatch(kObstacle, "obstacle");
  if (!map_.sources.empty()) {
    draw_marker({(at.x + 9 - left_) / px_per_m_, map_.height - (at.y - top_) / px_per_m_}, kSource,
                6);
    put_text(image_, "source", at + cv::Point(24, 5), 0.45, kText);
  }
}

void MapCanvas::draw_title(const std::string& title) {
  put_text(image_, title, cv::Point(left_, top_ - 14), 0.55, kText);
}

void MapCanvas::draw_map() {
  draw_free_space();
  draw_obstacles();
  draw_walls_and_openings();
  draw_sources();
  draw_axes_and_scale();
  std::ostringstream title;
  title << (map_.name.empty() ? "map" : map_.name) << "  (" << format_number(map_.width) << " x "
        << format_number(map_.height) << " m, " << map_.obstacles.size() << " obstacles)";
  draw_title(title.str());
}

void MapCanvas::draw_field(const Grid<double>& field, double lo, double hi, int colormap) {
  const GridShape& g = field.shape;
  cv::Mat grey(g.ny, g.nx, CV_8U), valid(g.ny, g.nx, CV_8U);
  const double span = hi > lo ? hi - lo : 1.0;
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      const double v = field(i, j);
      const int row = g.ny - 1 - j;  // image rows run top-down
      valid.at<uchar>(row, i) = std::isnan(v) ? 0 : 255;
      grey.at<uchar>(row, i) =
          static_cast<uchar>(std::lround(255.0 * std::clamp((v - lo) / span, 0.0, 1.0)));
    }
  cv::Mat colour;
  cv::applyColorMap(grey, colour, colormap);
  const cv::Point a = pixel({0, map_.height}), b = pixel({map_.width, 0});
  const cv::Size size(b.x - a.x, b.y - a.y);
  cv::Mat scaled, mask;
  cv::resize(colour, scaled, size, 0, 0, cv::INTER_NEAREST);
  cv::resize(valid, mask, size, 0, 0, cv::INTER_NEAREST);
  scaled.copyTo(image_(cv::Rect(a, size)), mask);
}

void MapCanvas::draw_colour_bar(double lo, double hi, const std::string& label, int colormap) {
  const cv::Point top = pixel({map_.width, map_.height}) + cv::Point(28, 0);
  const int height = pixel({0, 0}).y - top.y, width = 16;
  cv::Mat ramp(height, 1, CV_8U);
  for (int r = 0; r < height; ++r)
    ramp.at<uchar>(r, 0) = static_cast<uchar>(255 - (255 * r) / std::max(1, height - 1));
  cv::Mat colour, wide;
  cv::applyColorMap(ramp, colour, colormap);
  cv::resize(colour, wide, cv::Size(width, height), 0, 0, cv::INTER_NEAREST);
  wide.copyTo(image_(cv::Rect(top, wide.size())));
  cv::rectangle(image_, cv::Rect(top, wide.size()), kText, 1);
  put_text(image_, format_number(hi), top + cv::Point(width + 4, 8), 0.4, kText);
  put_text(image_, format_number(lo), top + cv::Point(width + 4, height), 0.4, kText);
  put_text(image_, label, top + cv::Point(-8, -10), 0.4, kText);
}

void MapCanvas::draw_path(const std::vector<Vec2>& path, const cv::Scalar& colour, int thickness) {
  std::vector<cv::Point> pts;
  for (Vec2 p : path)
    pts.push_back(fixed(to_px(p)));
  cv::polylines(image_, std::vector<std::vector<cv::Point>>{pts}, false, colour, thickness,
                cv::LINE_AA, kShift);
}

void write_png(const cv::Mat& image, const std::filesystem::path& path) {
  write_output_file(path, mark_png(encode_png(image)));
}

}  // namespace plumekit
