#include "map/map_render.hpp"

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
const cv::Scalar kWall(20, 20, 20);
const cv::Scalar kText(30, 30, 30);

constexpr double kScale = 1 << MapCanvas::kFixedShift;
constexpr int kShift = MapCanvas::kFixedShift;
constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;
// Text scale bounds: the floor keeps small pictures legible, the ceiling
// keeps labels from crowding out a large arena.
constexpr double kFontFloor = 0.4, kFontCeiling = 1.4;

cv::Point fixed_point(cv::Point2d p) {
  return {static_cast<int>(std::lround(p.x * kScale)), static_cast<int>(std::lround(p.y * kScale))};
}

}  // namespace

// ---- size checks ------------------------------------------------------------

namespace {

// Nominal margins around the arena, pixels, for the size and memory checks
// (the drawn margins follow the text they hold and stay close to these).
constexpr int kNominalMargins = 166;
// Longest side a picture may have: OpenCV draws in int pixel coordinates with
// 4 fractional bits, and no screen or page needs more.
constexpr double kMaxSidePx = 30000.0;
// Bytes per pixel at the peak: the BGR image, a tinted copy and the blend
// (map render --cells), and the PNG's rows.
constexpr double kBytesPerPixel = 4 * 3.0;

// Each side within kMaxSidePx, the memory within the limit
// (core/memory_limit.hpp).
void check_size(const Map& map, double px_per_m) {
  const double w = std::ceil(map.width * px_per_m) + kNominalMargins;
  const double h = std::ceil(map.height * px_per_m) + kNominalMargins;
  // The largest px_per_m whose picture meets both bounds, for the advice.
  const double side = std::max(map.width, map.height);
  double fit = (kMaxSidePx - kNominalMargins) / side;
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
}

}  // namespace

void RenderOptions::validate() const {
  check_range("render.px_per_m", px_per_m, 20.0, 1000.0, "pixels per metre",
              "pictures are laid out for 20 to 400; the default is 100");
}

// ---- text -------------------------------------------------------------------

cv::Size TextPainter::size(const std::string& text, double scale) const {
  int baseline = 0;
  const cv::Size s = cv::getTextSize(text, kFont, scale, thickness_, &baseline);
  return {s.width, s.height + baseline};
}

void TextPainter::put(cv::Mat& image, const std::string& text, cv::Point top_left) {
  put(image, text, top_left, scale_);
}

void TextPainter::put(cv::Mat& image, const std::string& text, cv::Point top_left, double scale) {
  int baseline = 0;
  const cv::Size s = cv::getTextSize(text, kFont, scale, thickness_, &baseline);
  cv::putText(image, text, top_left + cv::Point(0, s.height), kFont, scale, kText, thickness_,
              cv::LINE_AA);
  boxes_.emplace_back(top_left, cv::Size(s.width, s.height + baseline));
}

void TextPainter::put_on_white(cv::Mat& image, const std::string& text, cv::Point top_left) {
  cv::rectangle(image, cv::Rect(top_left, size(text)), kBackground, cv::FILLED);
  put(image, text, top_left);
}

void TextPainter::put_vertical(cv::Mat& image, const std::string& text, cv::Point top_left) {
  int baseline = 0;
  const cv::Size s = cv::getTextSize(text, kFont, scale_, thickness_, &baseline);
  cv::Mat flat(s.height + baseline, s.width, CV_8UC3, kBackground), upright;
  cv::putText(flat, text, {0, s.height}, kFont, scale_, kText, thickness_, cv::LINE_AA);
  cv::rotate(flat, upright, cv::ROTATE_90_COUNTERCLOCKWISE);
  const cv::Rect box(top_left, upright.size());
  // Clipped to the image, so that a bad layout shows in the test rather than crashing here.
  const cv::Rect inside = box & cv::Rect(0, 0, image.cols, image.rows);
  cv::Mat ink;
  cv::inRange(upright, kBackground, kBackground, ink);
  cv::bitwise_not(ink, ink);
  upright(inside - top_left).copyTo(image(inside), ink(inside - top_left));
  boxes_.push_back(box);
}

std::vector<std::string> wrap_words(const TextPainter& painter, const std::string& text, int width,
                                    double scale) {
  std::istringstream in(text);
  std::vector<std::string> lines;
  std::string word;
  while (in >> word) {
    if (!lines.empty() && painter.size(lines.back() + " " + word, scale).width <= width)
      lines.back() += " " + word;
    else
      lines.push_back(word);
  }
  return lines;
}

// ---- legends ----------------------------------------------------------------

namespace {

int legend_gap(const TextPainter& text) {
  return std::max(4, text.size("Ag").height / 2);
}

// A symbol in a box two text heights wide and one high, its top-left at `at`.
void draw_legend_symbol(cv::Mat& image, const LegendEntry& e, cv::Point at, int h, int thickness) {
  const int w = 2 * h;
  const cv::Point c = at + cv::Point(w / 2, h / 2);
  const int r = std::max(3, h / 2 - 1);
  // A pale mark (e.g. white streamlines) sits on grey, as it does on the fields it is drawn over.
  if (e.colour[0] + e.colour[1] + e.colour[2] > 600)
    cv::rectangle(image, at, at + cv::Point(w - 1, h - 1), cv::Scalar(120, 120, 120), cv::FILLED);
  switch (e.symbol) {
    case LegendEntry::Symbol::Swatch:
      cv::rectangle(image, at + cv::Point(1, 2), at + cv::Point(w - 2, h - 3), e.colour,
                    cv::FILLED);
      break;
    case LegendEntry::Symbol::Dot:
      cv::circle(image, c, r, e.colour, cv::FILLED, cv::LINE_AA);
      break;
    case LegendEntry::Symbol::Line:
      cv::line(image, at + cv::Point(1, h / 2), at + cv::Point(w - 2, h / 2), e.colour,
               std::max(2, h / 5), cv::LINE_AA);
      break;
    case LegendEntry::Symbol::Cross:
      cv::line(image, c + cv::Point(-r, -r), c + cv::Point(r, r), e.colour, 2, cv::LINE_AA);
      cv::line(image, c + cv::Point(-r, r), c + cv::Point(r, -r), e.colour, 2, cv::LINE_AA);
      break;
    case LegendEntry::Symbol::Ring:
      cv::circle(image, c, r, e.colour, std::max(2, thickness), cv::LINE_AA);
      break;
  }
}

}  // namespace

LegendLayout plan_legend(const TextPainter& text, const std::vector<LegendEntry>& entries,
                         int width) {
  const int h = text.size("Ag").height, gap = legend_gap(text);
  LegendLayout l;
  l.row_height = h + gap / 2;
  int row_w = 0;
  for (int k = 0; k < static_cast<int>(entries.size()); ++k) {
    const int w = 2 * h + gap / 2 + text.size(entries[k].text).width;
    l.widest = std::max(l.widest, w);
    if (l.rows.empty() || row_w + 2 * gap + w > width - 2 * gap) {
      l.rows.push_back({});
      row_w = -2 * gap;
    }
    l.rows.back().push_back(k);
    row_w += 2 * gap + w;
  }
  return l;
}

void draw_legend(cv::Mat& image, TextPainter& text, const std::vector<LegendEntry>& entries,
                 const LegendLayout& layout, cv::Point at) {
  const int h = text.size("Ag").height, gap = legend_gap(text);
  int y = at.y;
  for (const std::vector<int>& row : layout.rows) {
    int x = at.x;
    for (int k : row) {
      const LegendEntry& e = entries[k];
      draw_legend_symbol(image, e, {x, y}, h, text.thickness());
      x += 2 * h + gap / 2;
      text.put(image, e.text, {x, y});
      x += text.size(e.text).width + 2 * gap;
    }
    y += layout.row_height;
  }
}

// ---- layout -----------------------------------------------------------------

namespace {

// Tick values along one axis of `length` metres that starts at `origin` in
// the map frame: the multiples of `step` in between, in the map frame.
std::vector<double> ticks(double origin, double length, double step) {
  std::vector<double> t;
  const double first = std::ceil((origin - 1e-9) / step);
  for (double k = first; k * step <= origin + length + 1e-9; ++k)
    t.push_back(k * step + 0.0);  // + 0.0: no "-0"
  return t;
}

// The smallest step of the 1-2-5 series whose tick spacing holds `needed(step)` pixels.
template <typename Needed>
double tick_step(double px_per_m, Needed needed) {
  for (double decade = 0.01;; decade *= 10)
    for (double m : {1.0, 2.0, 5.0})
      if (m * decade * px_per_m >= needed(m * decade)) return m * decade;
}

int widest_word(const TextPainter& painter, const std::string& text, double scale) {
  std::istringstream in(text);
  std::string word;
  int w = 0;
  while (in >> word)
    w = std::max(w, painter.size(word, scale).width);
  return w;
}

std::vector<std::string> bar_labels(const ColourBar& bar) {
  if (bar.uniform) return {bar.lo == 0.0 ? "all zero" : "all " + compact(bar.lo)};
  return {compact(bar.hi), compact(0.5 * (bar.lo + bar.hi)), compact(bar.lo)};
}

constexpr double kTitleScale = 1.2;  // title text relative to the rest

}  // namespace

MapCanvas::MapCanvas(const Map& map, const RenderOptions& options, Frame frame)
    : map_(map), px_per_m_(options.px_per_m), frame_(std::move(frame)) {
  options.validate();
  check_size(map, px_per_m_);
  plan_layout();
}

// Sizes every margin from the text it will hold, then allocates the image.
void MapCanvas::plan_layout() {
  const int arena_w = static_cast<int>(std::ceil(map_.width * px_per_m_));
  const int arena_h = static_cast<int>(std::ceil(map_.height * px_per_m_));
  font_ = std::clamp(0.45 * std::max(arena_w, arena_h) / 1000.0, kFontFloor, kFontCeiling);
  mark_scale_ = font_ / kFontFloor;
  thickness_ = font_ < 0.7 ? 1 : 2;
  text_ = TextPainter(font_, thickness_);
  text_h_ = text_.size("Ag").height;
  gap_ = std::max(4, text_h_ / 2);
  tick_ = std::max(4, text_h_ / 3);
  auto widest_tick = [&](double origin, double length, double step) {
    int w = 0;
    for (double t : ticks(origin, length, step))
      w = std::max(w, text_.size(compact(t)).width);
    return w;
  };
  const Vec2 origin = map_.frame.origin;
  step_x_ = tick_step(px_per_m_,
                      [&](double s) { return widest_tick(origin.x, map_.width, s) + 3 * gap_; });
  step_y_ = tick_step(px_per_m_, [&](double) { return 3 * text_h_; });
  // One step on both axes where the two differ, so a metre looks the same either way.
  step_x_ = step_y_ = std::max(step_x_, step_y_);
  const std::vector<double> x_ticks = ticks(origin.x, map_.width, step_x_);
  const int x_last_w = x_ticks.empty() ? 0 : text_.size(compact(x_ticks.back())).width;
  left_ = gap_ + text_h_ + gap_ + widest_tick(origin.y, map_.height, step_y_) + gap_ / 2 + tick_;

  // Right margin: half the last x label, or the colour bar with its value
  // labels and its own label turned upright.
  int right = x_last_w / 2 + gap_;
  bar_len_ = 0;
  if (frame_.colour_bar) {
    int labels_w = 0;
    for (const std::string& s : bar_labels(*frame_.colour_bar))
      labels_w = std::max(labels_w, text_.size(s).width);
    const int bar_off = std::max(2 * gap_, x_last_w / 2 + gap_);
    bar_x_ = left_ + arena_w + bar_off;
    right = bar_off + std::max(12, text_h_) + tick_ + gap_ / 2 + labels_w + gap_ + text_h_ + gap_;
    bar_len_ =
        std::max({arena_h, text_.size(frame_.colour_bar->label).width + 2 * gap_, 4 * text_h_});
  }

  // Width: the arena and its margins, or more where a legend entry, a title
  // word or the x label needs it.
  const double title_font = font_ * kTitleScale;
  int width = left_ + arena_w + right;
  width = std::max(width, widest_word(text_, frame_.title, title_font) + 2 * gap_);
  width = std::max(width, text_.size("x [m]").width + 2 * gap_);
  collect_legend();
  width = std::max(width, plan_legend(text_, legend_, width).widest + 2 * gap_);
  legend_layout_ = plan_legend(text_, legend_, width);
  title_lines_ = wrap_words(text_, frame_.title, width - 2 * gap_, title_font);
  const int title_h = text_.size("Ag", title_font).height;

  top_ = gap_ + static_cast<int>(title_lines_.size()) * (title_h + gap_ / 2) + gap_ + text_h_ / 2;
  body_h_ = std::max(arena_h + tick_ + gap_ / 2 + text_h_ + gap_ / 2 + text_h_,
                     bar_len_ + text_h_ / 2 + gap_);
  const int legend_h = legend_layout_.height();
  const int height = top_ + body_h_ + gap_ + legend_h + gap_;
  image_ = cv::Mat(height, width, CV_8UC3, kBackground);
}

namespace {

// "inlet (left, 1 m/s uniform)", "outlet (right)", "inlets (3, 0.5-1 m/s)",
// "outlet (on an obstacle)".
std::string openings_legend(const Map& map, bool inlets) {
  std::vector<const Opening*> list;
  for (const Opening& o : map.openings)
    if (o.is_inlet() == inlets) list.push_back(&o);
  if (list.empty()) return inlets ? "inlet" : "outlet";
  const std::string noun = inlets ? "inlet" : "outlet";
  if (list.size() == 1) {
    const Opening& o = *list[0];
    const auto wall = map.wall_of(o);
    std::string where = wall ? to_string(*wall) : "on an obstacle";
    if (inlets) where += ", " + compact(o.speed) + " m/s " + to_string(o.profile);
    return noun + " (" + where + ")";
  }
  std::string s = noun + "s (" + std::to_string(list.size());
  if (inlets) {
    double lo = list[0]->speed, hi = lo;
    for (const Opening* o : list)
      lo = std::min(lo, o->speed), hi = std::max(hi, o->speed);
    s += ", " + (lo == hi ? compact(lo) : compact(lo) + "-" + compact(hi)) + " m/s";
  }
  return s + ")";
}

}  // namespace

// The legend's entries: the map's, then the picture's.
void MapCanvas::collect_legend() {
  legend_.clear();
  if (frame_.map_legend) {
    legend_.push_back({LegendEntry::Symbol::Swatch, colours::kInlet, openings_legend(map_, true)});
    legend_.push_back(
        {LegendEntry::Symbol::Swatch, colours::kOutlet, openings_legend(map_, false)});
    if (!map_.obstacles.empty())
      legend_.push_back({LegendEntry::Symbol::Swatch, colours::kObstacle, "obstacle"});
    if (!map_.sources.empty())
      legend_.push_back({LegendEntry::Symbol::Dot, colours::kSource, "source"});
  }
  legend_.insert(legend_.end(), frame_.legend.begin(), frame_.legend.end());
}

cv::Rect MapCanvas::arena_rect() const {
  const cv::Point a = pixel({0, map_.height}), b = pixel({map_.width, 0});
  return {a, b};
}

cv::Point2d MapCanvas::to_px(Vec2 p) const {
  return {left_ + p.x * px_per_m_, top_ + (map_.height - p.y) * px_per_m_};
}

cv::Point MapCanvas::pixel(Vec2 p) const {
  const cv::Point2d q = to_px(p);
  return {static_cast<int>(std::lround(q.x)), static_cast<int>(std::lround(q.y))};
}

cv::Point MapCanvas::fixed(Vec2 p) const {
  return fixed_point(to_px(p));
}

// ---- the arena --------------------------------------------------------------

void MapCanvas::draw_free_space() {
  cv::rectangle(image_, pixel({0, map_.height}), pixel({map_.width, 0}), kFreeSpace, cv::FILLED);
}

void MapCanvas::draw_obstacles() {
  for (const Polygon& poly : map_.obstacles) {
    std::vector<cv::Point> pts;
    for (Vec2 v : poly)
      pts.push_back(fixed(v));
    const std::vector<std::vector<cv::Point>> polys{pts};
    cv::fillPoly(image_, polys, colours::kObstacle, cv::LINE_AA, kShift);
    cv::polylines(image_, polys, true, colours::kObstacle * 0.6, 1, cv::LINE_AA, kShift);
  }
}

void MapCanvas::draw_walls_and_openings() {
  const double w = map_.width, h = map_.height;
  cv::rectangle(image_, pixel({0, h}), pixel({w, 0}), kWall, 2, cv::LINE_AA);
  const int band = static_cast<int>(std::lround(6 * mark_scale_));
  const int arrow_w = std::max(2, static_cast<int>(std::lround(2 * mark_scale_)));

  // An opening: a thick coloured band on its stretch with arrows across it.
  auto opening = [&](const Opening& o, const cv::Scalar& colour, bool inward) {
    cv::line(image_, fixed(o.from), fixed(o.to), colour, band, cv::LINE_AA, kShift);
    const Vec2 normal = map_.inward_normal(o);
    const Vec2 along = o.vertical() ? Vec2{0, 1} : Vec2{1, 0};
    const Vec2 start = o.vertical() ? Vec2{o.line(), o.lo()} : Vec2{o.lo(), o.line()};
    // At most a fifth of the arena's short side, so arrows never cross a small arena.
    const double short_side = std::min(map_.width, map_.height);
    const double arrow = std::min(28.0 * mark_scale_ / px_per_m_, 0.2 * short_side);  // metres
    const int count = std::max(1, static_cast<int>(o.length() / (60.0 * mark_scale_ / px_per_m_)));
    for (int k = 0; k < count; ++k) {
      const Vec2 base = start + ((k + 0.5) * o.length() / count) * along;
      // Inlet arrows point into the free space, outlet arrows out of it.
      const Vec2 from = inward ? base : base + arrow * normal;
      const Vec2 to = inward ? base + arrow * normal : base;
      cv::arrowedLine(image_, pixel(from), pixel(to), colour, arrow_w, cv::LINE_AA, 0, 0.35);
    }
  };
  for (const Opening& o : map_.openings)
    opening(o, o.is_inlet() ? colours::kInlet : colours::kOutlet, o.is_inlet());
}

void MapCanvas::draw_marker(Vec2 p, const cv::Scalar& colour, int radius_px) {
  const int r = static_cast<int>(std::lround(radius_px * mark_scale_ * kScale));
  cv::circle(image_, fixed(p), r + 2 * static_cast<int>(kScale), kBackground, cv::FILLED,
             cv::LINE_AA, kShift);
  cv::circle(image_, fixed(p), r, colour, cv::FILLED, cv::LINE_AA, kShift);
}

void MapCanvas::draw_cross(Vec2 p, const cv::Scalar& colour) {
  const cv::Point c = pixel(p);
  const int r = static_cast<int>(std::lround(8 * mark_scale_));
  const int w = std::max(2, static_cast<int>(std::lround(2 * mark_scale_)));
  for (int t : {w + 3, w}) {
    const cv::Scalar col = t == w ? colour : kBackground;
    cv::line(image_, c + cv::Point(-r, -r), c + cv::Point(r, r), col, t, cv::LINE_AA);
    cv::line(image_, c + cv::Point(-r, r), c + cv::Point(r, -r), col, t, cv::LINE_AA);
  }
}

void MapCanvas::draw_ring(Vec2 p, const cv::Scalar& colour, int radius_px) {
  const int r = static_cast<int>(std::lround(radius_px * mark_scale_ * kScale));
  const int width =
      std::max(thickness_, static_cast<int>(std::lround(radius_px * mark_scale_ / 4)));
  cv::circle(image_, fixed(p), r, colour, width, cv::LINE_AA, kShift);
}

void MapCanvas::draw_sources() {
  for (std::size_t k = 0; k < map_.sources.size(); ++k)
    draw_source(map_.sources[k], "S" + std::to_string(k));
}

void MapCanvas::draw_source(Vec2 p, const std::string& label) {
  draw_marker(p, colours::kSource, 6);
  // Up and right of the marker, kept inside the arena.
  const cv::Size s = text_.size(label);
  const cv::Rect arena = arena_rect();
  const int off = static_cast<int>(std::lround(9 * mark_scale_));
  cv::Point at = pixel(p) + cv::Point(off, -off - s.height);
  if (at.x + s.width > arena.br().x - 2) at.x = pixel(p).x - off - s.width;
  at.x = std::clamp(at.x, arena.x + 2, std::max(arena.x + 2, arena.br().x - 2 - s.width));
  at.y = std::clamp(at.y, arena.y + 2, std::max(arena.y + 2, arena.br().y - 2 - s.height));
  text_.put_on_white(image_, label, at);
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
  const cv::Rect arena = arena_rect();
  cv::Mat scaled, mask;
  cv::resize(colour, scaled, arena.size(), 0, 0, cv::INTER_NEAREST);
  cv::resize(valid, mask, arena.size(), 0, 0, cv::INTER_NEAREST);
  scaled.copyTo(image_(arena), mask);
}

void MapCanvas::draw_path(const std::vector<Vec2>& path, const cv::Scalar& colour, int thickness) {
  std::vector<cv::Point> pts;
  for (Vec2 p : path)
    pts.push_back(fixed(p));
  const int t = std::max(1, static_cast<int>(std::lround(thickness * mark_scale_)));
  cv::polylines(image_, std::vector<std::vector<cv::Point>>{pts}, false, colour, t, cv::LINE_AA,
                kShift);
}

// ---- the margins ------------------------------------------------------------

void MapCanvas::draw_axes() {
  const cv::Rect arena = arena_rect();
  // Tick labels are map-frame coordinates.
  const Vec2 origin = map_.frame.origin;
  for (double x : ticks(origin.x, map_.width, step_x_)) {
    const cv::Point p = pixel({x - origin.x, 0});
    cv::line(image_, p, p + cv::Point(0, tick_), kText, thickness_, cv::LINE_AA);
    const std::string s = compact(x);
    const int w = text_.size(s).width;
    text_.put(image_, s, p + cv::Point(-w / 2, tick_ + gap_ / 2));
  }
  const int x_label_w = text_.size("x [m]").width;
  const int x_label_x = std::max(gap_, arena.x + arena.width / 2 - x_label_w / 2);
  text_.put(image_, "x [m]", {x_label_x, arena.br().y + tick_ + gap_ + text_h_ + gap_ / 2});
  for (double y : ticks(origin.y, map_.height, step_y_)) {
    const cv::Point p = pixel({0, y - origin.y});
    cv::line(image_, p, p - cv::Point(tick_, 0), kText, thickness_, cv::LINE_AA);
    const std::string s = compact(y);
    const int w = text_.size(s).width;
    text_.put(image_, s, p + cv::Point(-tick_ - gap_ / 2 - w, -text_h_ / 2));
  }
  const int y_label_len = text_.size(frame_.y_label).width;
  const int y_label_y = std::max(top_, arena.y + arena.height / 2 - y_label_len / 2);
  text_.put_vertical(image_, frame_.y_label, {gap_, y_label_y});
}

namespace {

// The metre axes' layout: one tick step for both axes (a metre looks the same either way).
struct MetreAxes {
  int text_h, gap, tick;
  double step;
  int widest_y;  // the widest y tick label
};

MetreAxes metre_axes(const TextPainter& text, const cv::Rect& box, double px_per_m, Vec2 origin) {
  MetreAxes a;
  a.text_h = text.size("Ag").height;
  a.gap = std::max(4, a.text_h / 2);
  a.tick = std::max(4, a.text_h / 3);
  const double width = box.width / px_per_m, height = box.height / px_per_m;
  const auto widest = [&](double o, double length, double step) {
    int w = 0;
    for (double t : ticks(o, length, step))
      w = std::max(w, text.size(compact(t)).width);
    return w;
  };
  const double sx =
      tick_step(px_per_m, [&](double s) { return widest(origin.x, width, s) + 3 * a.gap; });
  const double sy = tick_step(px_per_m, [&](double) { return 3 * a.text_h; });
  a.step = std::max(sx, sy);
  a.widest_y = widest(origin.y, height, a.step);
  return a;
}

}  // namespace

AxesMargins metre_axes_margins(const TextPainter& text, const cv::Rect& box, double px_per_m,
                               Vec2 origin) {
  const MetreAxes a = metre_axes(text, box, px_per_m, origin);
  return {a.tick + a.gap / 2 + a.widest_y + a.gap + a.text_h + a.gap,
          a.tick + a.gap / 2 + a.text_h + a.gap + a.text_h + a.gap / 2};
}

void draw_metre_axes(cv::Mat& image, TextPainter& text, const cv::Rect& box, double px_per_m,
                     Vec2 origin, const std::string& x_label, const std::string& y_label) {
  const MetreAxes a = metre_axes(text, box, px_per_m, origin);
  const int bottom = box.y + box.height;
  for (double x : ticks(origin.x, box.width / px_per_m, a.step)) {
    const cv::Point p(box.x + static_cast<int>(std::lround((x - origin.x) * px_per_m)), bottom);
    cv::line(image, p, p + cv::Point(0, a.tick), kText, text.thickness(), cv::LINE_AA);
    const std::string s = compact(x);
    text.put(image, s, p + cv::Point(-text.size(s).width / 2, a.tick + a.gap / 2));
  }
  for (double y : ticks(origin.y, box.height / px_per_m, a.step)) {
    const cv::Point p(box.x, bottom - static_cast<int>(std::lround((y - origin.y) * px_per_m)));
    cv::line(image, p, p - cv::Point(a.tick, 0), kText, text.thickness(), cv::LINE_AA);
    const std::string s = compact(y);
    text.put(image, s, p + cv::Point(-a.tick - a.gap / 2 - text.size(s).width, -a.text_h / 2));
  }
  if (!x_label.empty())
    text.put(image, x_label,
             {box.x + box.width / 2 - text.size(x_label).width / 2,
              bottom + a.tick + a.gap / 2 + a.text_h + a.gap});
  if (!y_label.empty())
    text.put_vertical(image, y_label,
                      {box.x - a.tick - a.gap / 2 - a.widest_y - a.gap - a.text_h,
                       box.y + box.height / 2 - text.size(y_label).width / 2});
}

void MapCanvas::draw_colour_bar(const ColourBar& bar) {
  const int width = std::max(12, text_h_);
  const cv::Point top(bar_x_, top_);
  cv::Mat ramp(bar_len_, 1, CV_8U);
  for (int r = 0; r < bar_len_; ++r)
    ramp.at<uchar>(r, 0) =
        bar.uniform ? 0 : static_cast<uchar>(255 - (255 * r) / std::max(1, bar_len_ - 1));
  cv::Mat colour, wide;
  cv::applyColorMap(ramp, colour, bar.colormap);
  cv::resize(colour, wide, cv::Size(width, bar_len_), 0, 0, cv::INTER_NEAREST);
  wide.copyTo(image_(cv::Rect(top, wide.size())));
  cv::rectangle(image_, cv::Rect(top, wide.size()), kText, 1);

  const std::vector<std::string> labels = bar_labels(bar);
  // Value labels at the ends and the middle; the middle one only where it has room.
  const bool room_for_middle = bar_len_ >= 5 * text_h_;
  int labels_w = 0;
  for (std::size_t k = 0; k < labels.size(); ++k) {
    if (labels.size() == 3 && k == 1 && !room_for_middle) continue;
    const int y = labels.size() == 1 ? top.y + bar_len_ / 2
                                     : top.y + static_cast<int>(k) * (bar_len_ - 1) / 2;
    const cv::Point tick_at(top.x + width, y);
    cv::line(image_, tick_at, tick_at + cv::Point(tick_, 0), kText, thickness_);
    text_.put(image_, labels[k], tick_at + cv::Point(tick_ + gap_ / 2, -text_h_ / 2));
    labels_w = std::max(labels_w, text_.size(labels[k]).width);
  }
  for (const std::string& s : labels)
    labels_w = std::max(labels_w, text_.size(s).width);
  const int label_len = text_.size(bar.label).width;
  text_.put_vertical(
      image_, bar.label,
      {top.x + width + tick_ + gap_ / 2 + labels_w + gap_, top.y + bar_len_ / 2 - label_len / 2});
}

void MapCanvas::draw_title() {
  const double scale = font_ * 1.2;
  const int h = text_.size("Ag", scale).height;
  int y = gap_;
  for (const std::string& line : title_lines_) {
    text_.put(image_, line, {gap_, y}, scale);
    y += h + gap_ / 2;
  }
}

Picture MapCanvas::finish() {
  draw_axes();
  if (frame_.colour_bar) draw_colour_bar(*frame_.colour_bar);
  draw_legend(image_, text_, legend_, legend_layout_, {gap_, top_ + body_h_ + gap_});
  draw_title();
  return {image_, text_.boxes(), arena_rect()};
}

void write_png(const cv::Mat& image, const std::filesystem::path& path) {
  write_output_file(path, mark_png(encode_png(image)));
}

}  // namespace plumekit
