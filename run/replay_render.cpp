#include "run/replay_render.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <memory>
#include <sstream>

#include <opencv2/imgproc.hpp>

#include "core/progress.hpp"
#include "map/map_render.hpp"
#include "run/replay_recorder.hpp"

namespace plumekit::run {

namespace {

// A team's robots (BGR), as trajectory.png colours them after the first.
const cv::Scalar kRobots[] = {{40, 40, 40},   {20, 120, 230}, {200, 130, 0},
                              {160, 40, 160}, {40, 40, 200},  {60, 160, 60}};
cv::Scalar robot_colour(int k) {
  return kRobots[static_cast<std::size_t>(k) % (sizeof(kRobots) / sizeof(kRobots[0]))];
}

std::string fixed(double v, int digits) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(digits) << v;
  return s.str();
}

// A colour map's 256 colours, level 0 white (no gas, no belief): a 256 x 1 BGR lookup table.
// `root`: level k takes the colour of sqrt(k / 255), so that a belief's tails show beside its peak.
cv::Mat colour_table(int colormap, bool reverse, bool root = false) {
  cv::Mat levels(1, 256, CV_8U);
  for (int k = 0; k < 256; ++k) {
    const int v = root ? static_cast<int>(std::lround(255.0 * std::sqrt(k / 255.0))) : k;
    levels.at<uchar>(0, k) = static_cast<uchar>(reverse ? 255 - v : v);
  }
  cv::Mat table;
  cv::applyColorMap(levels, table, colormap);
  // Gas fades in from white: a faint trace is a pale tint of the colour map's first colour.
  for (int k = 0; k < 256; ++k) {
    const double a = k == 0 ? 0.0 : std::min(1.0, 0.25 + 0.75 * k / 64.0);
    cv::Vec3b& c = table.at<cv::Vec3b>(0, k);
    for (int ch = 0; ch < 3; ++ch)
      c[ch] = static_cast<uchar>(std::lround(255.0 * (1.0 - a) + c[ch] * a));
  }
  return table;
}

// One map panel: the map drawn once (free space, obstacles, axes, title, legend), fitted into
// its box, and where its arena's free space lies.
struct MapPanel {
  std::unique_ptr<MapCanvas> canvas;
  cv::Mat background;  // the panel, scaled to fit its box
  double scale = 1.0;  // panel pixels per canvas pixel
  cv::Rect arena;      // in the panel
  cv::Mat free;        // over the arena: 255 where the free space shows
  cv::Point2d px(Vec2 p) const {
    const cv::Point2d c = canvas->to_px(p);
    return {c.x * scale, c.y * scale};
  }
};

MapPanel map_panel(const Map& map, cv::Size box, const Frame& frame) {
  MapPanel panel;
  double ppm = std::clamp(std::min(box.width / map.width, box.height / map.height), 20.0, 400.0);
  for (int attempt = 0;; ++attempt) {
    panel.canvas = std::make_unique<MapCanvas>(map, RenderOptions{ppm}, frame);
    panel.canvas->draw_free_space();
    const cv::Rect a = panel.canvas->arena_rect();
    const cv::Mat bare = panel.canvas->image()(a).clone();
    panel.canvas->draw_obstacles();
    panel.canvas->draw_walls_and_openings();
    cv::Mat same;
    cv::compare(bare.reshape(1), panel.canvas->image()(a).reshape(1), same, cv::CMP_EQ);
    cv::Mat free = same.reshape(3);
    std::vector<cv::Mat> ch;
    cv::split(free, ch);
    cv::bitwise_and(ch[0], ch[1], panel.free);
    cv::bitwise_and(panel.free, ch[2], panel.free);
    const Picture p = panel.canvas->finish();
    const double fit = std::min(static_cast<double>(box.width) / p.image.cols,
                                static_cast<double>(box.height) / p.image.rows);
    if (fit >= 1.0 || ppm <= 20.0 || attempt >= 8) {
      panel.scale = std::min(1.0, fit);
      if (panel.scale < 1.0) {
        cv::resize(p.image, panel.background, cv::Size(), panel.scale, panel.scale, cv::INTER_AREA);
        cv::resize(panel.free, panel.free, cv::Size(), panel.scale, panel.scale, cv::INTER_NEAREST);
        panel.arena = cv::Rect(cv::Point(static_cast<int>(std::lround(a.x * panel.scale)),
                                         static_cast<int>(std::lround(a.y * panel.scale))),
                               panel.free.size());
      } else {
        panel.background = p.image;
        panel.arena = a;
      }
      return panel;
    }
    ppm = std::max(20.0, ppm * fit * 0.98);
  }
}

// `levels` (a grid of 8-bit levels, row 0 at y = 0) through `table` over the panel's free space.
void paint_levels(cv::Mat& image, const MapPanel& panel, const std::uint8_t* levels,
                  const GridShape& g, const cv::Mat& table) {
  cv::Mat grid(g.ny, g.nx, CV_8U);
  for (int j = 0; j < g.ny; ++j)
    std::copy_n(levels + g.index(0, j), g.nx, grid.ptr<uchar>(g.ny - 1 - j));
  cv::Mat scaled, grey3, colour;
  cv::resize(grid, scaled, panel.arena.size(), 0, 0, cv::INTER_LINEAR);
  cv::cvtColor(scaled, grey3, cv::COLOR_GRAY2BGR);
  cv::LUT(grey3, table, colour);
  colour.copyTo(image(panel.arena), panel.free);
}

cv::Point fixed_point(cv::Point2d p) {
  return {static_cast<int>(std::lround(p.x * 16)), static_cast<int>(std::lround(p.y * 16))};
}

void dot(cv::Mat& image, cv::Point2d p, int radius, const cv::Scalar& fill, const cv::Scalar& rim) {
  cv::circle(image, fixed_point(p), radius * 16, fill, cv::FILLED, cv::LINE_AA, 4);
  cv::circle(image, fixed_point(p), radius * 16, rim, 1, cv::LINE_AA, 4);
}

void cross(cv::Mat& image, cv::Point2d p, int half, const cv::Scalar& colour, int thickness) {
  const cv::Point2d a(half, half), b(half, -half);
  cv::line(image, fixed_point(p - a), fixed_point(p + a), colour, thickness, cv::LINE_AA, 4);
  cv::line(image, fixed_point(p - b), fixed_point(p + b), colour, thickness, cv::LINE_AA, 4);
}

}  // namespace

class ReplayPainter::Panels {
 public:
  Panels(const Replay& r, cv::Size size) : r_(r), size_(size) {
    header_ = std::max(48, size.height / 13);
    const int half = size.width / 2, body = size.height - header_;
    std::vector<LegendEntry> legend = {
        {LegendEntry::Symbol::Dot, robot_colour(0), r.robots > 1 ? "robots" : "robot"},
        {LegendEntry::Symbol::Dot, cv::Scalar(255, 255, 255), "stop (coloured by its reading)"},
        {LegendEntry::Symbol::Cross, colours::kEstimate, "estimate"}};
    Map with_source = r.map;
    with_source.sources = {r.source};
    if (r.side) {
      tunnel_layout(with_source, legend, half, body);
    } else {
      const cv::Size world_box(half, body);
      worlds_.emplace_back(
          map_panel(with_source, world_box,
                    Frame{"the world: gas (log scale) and robots", std::nullopt, legend, true}),
          false);
      const int world_rows = worlds_[0].panel.background.rows;
      // The readings over time go under both maps where a wide map leaves room, else under the
      // belief.
      const int below = body - world_rows;
      cv::Size belief_box(size.width - half, body * 62 / 100);
      if (below >= body * 3 / 10) {
        belief_box.height = world_rows;
        series_ = cv::Rect(0, header_ + world_rows, size.width, below);
      } else {
        series_ = cv::Rect(half, header_ + belief_box.height, size.width - half,
                           body - belief_box.height);
      }
      beliefs_.emplace_back(
          map_panel(with_source, belief_box, Frame{"the method's belief", std::nullopt, {}, false}),
          false);
      worlds_[0].at = {(world_box.width - worlds_[0].panel.background.cols) / 2, header_};
      beliefs_[0].at = {half + (belief_box.width - beliefs_[0].panel.background.cols) / 2, header_};
    }
    gas_ = colour_table(cv::COLORMAP_INFERNO, true);
    belief_table_ = colour_table(cv::COLORMAP_VIRIDIS, true, true);
    for (const ReplayStop& s : r.stops)
      top_reading_ = std::max(top_reading_, s.value);
    for (const ReplayReading& s : r.readings)
      top_reading_ = std::max(top_reading_, s.value);
    top_reading_ = std::max(top_reading_, 1.0);
  }

  cv::Mat frame(int k) {
    cv::Mat image(size_, CV_8UC3, cv::Scalar(255, 255, 255));
    const double t = r_.time_of(k);
    add_readings(t);
    for (View& v : worlds_)
      draw_world(image, v, k, t);
    for (const View& v : beliefs_)
      draw_belief(image, v, t);
    draw_series(image, t);
    draw_header(image, t);
    return image;
  }

 private:
  // A map panel where the frame shows it; `side`: the tunnel from the side (x, z). The layers of
  // the readings on the way drawn so far over a world view (add_readings).
  struct View {
    MapPanel panel;
    cv::Point at;
    bool side = false;
    cv::Mat dots, dots_mask;
    View(MapPanel p, bool is_side) : panel(std::move(p)), side(is_side) {}
  };

  // The tunnel's views: from above over from the side (the same metres per pixel, so that x lines
  // up), the world's on the left and the belief's on the right, the readings over time below.
  void tunnel_layout(const Map& above, const std::vector<LegendEntry>& legend, int half, int body) {
    const ReplaySide& s = *r_.side;
    Map side = above;
    side.height = s.height;
    side.sources = {{r_.source.x, s.source_z}};
    for (Opening& o : side.openings)  // the tunnel's inlet and outlet span its walls
      if (o.vertical()) o.from.y = 0.0, o.to.y = s.height;
    const int views_h = body * 76 / 100;
    const std::string at_z = "from above, z = " + fixed(s.plane_z, 2) + " m";
    const std::string at_y = "from the side, y = " + fixed(s.plane_y, 2) + " m";
    const Frame top{"gas (log scale), " + at_z, std::nullopt, legend, true};
    Frame low{"gas, " + at_y, std::nullopt, {}, false};
    low.y_label = "z [m]";
    const Frame belief_top{"belief (x, y), summed over z", std::nullopt, {}, false};
    Frame belief_low{"belief (x, z), summed over y", std::nullopt, {}, false};
    belief_low.y_label = "z [m]";
    // Each column as wide as both views fit above each other at one scale (a view fitted to its
    // width alone has the column's scale).
    int width = half;
    for (int attempt = 0; attempt < 6; ++attempt) {
      worlds_.clear();
      beliefs_.clear();
      const cv::Size box(width, 100000);
      worlds_.emplace_back(map_panel(above, box, top), false);
      worlds_.emplace_back(map_panel(side, box, low), true);
      beliefs_.emplace_back(map_panel(above, box, belief_top), false);
      beliefs_.emplace_back(map_panel(side, box, belief_low), true);
      const int tall =
          std::max(worlds_[0].panel.background.rows + worlds_[1].panel.background.rows,
                   beliefs_[0].panel.background.rows + beliefs_[1].panel.background.rows);
      if (tall <= views_h) break;
      width = static_cast<int>(width * 0.98 * views_h / tall);
    }
    for (int col = 0; col < 2; ++col) {
      std::vector<View>& views = col == 0 ? worlds_ : beliefs_;
      const int x0 = col * half;
      views[0].at = {x0 + (half - views[0].panel.background.cols) / 2, header_};
      views[1].at = {x0 + (half - views[1].panel.background.cols) / 2,
                     header_ + views[0].panel.background.rows};
    }
    const int used = std::max(worlds_[1].at.y + worlds_[1].panel.background.rows,
                              beliefs_[1].at.y + beliefs_[1].panel.background.rows);
    series_ = cv::Rect(0, used, size_.width, size_.height - used);
  }

  // Where a view shows a point with its height z.
  static Vec2 seen(const View& v, Vec2 p, double z) { return v.side ? Vec2{p.x, z} : p; }

  // Colour of a reading on the gas scale.
  cv::Scalar reading_colour(double v) const {
    const int level = r_.plume_level(v);
    const cv::Vec3b c = gas_.at<cv::Vec3b>(0, std::max(level, 40));
    return {static_cast<double>(c[0]), static_cast<double>(c[1]), static_cast<double>(c[2])};
  }

  double robot_z(int k, int robot) const {
    return r_.side ? r_.side->z[static_cast<std::size_t>(k)][static_cast<std::size_t>(robot)] : 0.0;
  }

  void draw_world(cv::Mat& image, const View& v, int k, double t) {
    const MapPanel& w = v.panel;
    cv::Mat panel = w.background.clone();
    if (v.side) {
      const std::size_t cells = r_.side->plume_grid.size();
      paint_levels(panel, w, r_.side->plume.data() + static_cast<std::size_t>(k) * cells,
                   r_.side->plume_grid, gas_);
    } else {
      const std::size_t cells = r_.plume_grid.size();
      paint_levels(panel, w, r_.plume.data() + static_cast<std::size_t>(k) * cells, r_.plume_grid,
                   gas_);
    }
    // Each robot's way so far, from the frames' positions.
    for (int robot = 0; robot < r_.robots; ++robot) {
      std::vector<cv::Point> way;
      for (int f = 0; f <= k; ++f)
        way.push_back(fixed_point(w.px(seen(v, r_.positions[f][robot], robot_z(f, robot)))));
      cv::polylines(panel, std::vector<std::vector<cv::Point>>{way}, false, robot_colour(robot), 1,
                    cv::LINE_AA, 4);
    }
    v.dots.copyTo(panel, v.dots_mask);
    for (const ReplayStop& s : r_.stops)
      if (s.arrived_s <= t)
        dot(panel, w.px(seen(v, s.position, s.z)), 5, reading_colour(s.value),
            robot_colour(s.robot));
    cross(panel, w.px(seen(v, r_.source, r_.side ? r_.side->source_z : 0.0)), 6, colours::kSource,
          2);
    if (const ReplayStop* last = last_stop(t); last && r_.has_estimate)
      cross(panel, w.px(seen(v, last->estimate, last->estimate_z)), 6, colours::kEstimate, 2);
    for (int robot = 0; robot < r_.robots; ++robot)
      dot(panel, w.px(seen(v, r_.positions[k][robot], robot_z(k, robot))), 7, robot_colour(robot),
          cv::Scalar(255, 255, 255));
    panel.copyTo(image(cv::Rect(v.at, panel.size())));
  }

  void draw_belief(cv::Mat& image, const View& v, double t) {
    const MapPanel& b = v.panel;
    cv::Mat panel = b.background.clone();
    int latest = -1;
    for (std::size_t k = 0; k < r_.beliefs.size() && r_.beliefs[k].time_s <= t; ++k)
      latest = static_cast<int>(k);
    TextPainter text(0.45, 1);
    if (latest >= 0) {
      const GridShape& g = v.side ? r_.side->belief_grid : r_.belief_grid;
      const std::vector<std::uint8_t>& cells = v.side ? r_.side->belief_cells : r_.belief_cells;
      paint_levels(panel, b, cells.data() + latest * g.size(), g, belief_table_);
      if (r_.robots > 1)
        text.put_on_white(panel, "robot " + std::to_string(r_.beliefs[latest].robot + 1) + "'s",
                          b.arena.tl() + cv::Point(4, 4));
    } else if (!v.side) {
      text.put_on_white(panel,
                        r_.beliefs.empty() ? r_.method + " holds no belief" : "no reading yet",
                        b.arena.tl() + cv::Point(4, 4));
    }
    cross(panel, b.px(seen(v, r_.source, r_.side ? r_.side->source_z : 0.0)), 5, colours::kSource,
          2);
    if (const ReplayStop* last = last_stop(t); last && r_.has_estimate)
      cross(panel, b.px(seen(v, last->estimate, last->estimate_z)), 5, colours::kEstimate, 2);
    panel.copyTo(image(cv::Rect(v.at, panel.size())));
  }

  // The readings over time's plot area, and where a reading at `time` of `v` lies in it.
  cv::Rect series_box() const {
    return {series_.x + 56, series_.y + 24, series_.width - 72, series_.height - 60};
  }
  cv::Point2d series_at(double time, double v) const {
    const cv::Rect box = series_box();
    const double end = std::max(r_.ended_s, r_.time_of(r_.frames() - 1));
    const double x = box.x + box.width * std::clamp(time / std::max(end, 1.0), 0.0, 1.0);
    const double y =
        box.y + box.height * (1.0 - std::log1p(std::max(v, 0.0)) / std::log1p(top_reading_));
    return {x, y};
  }

  // The readings on the way up to `t` into their layers, which only grow with time (a long
  // mission has thousands; each frame copies the layers instead of drawing them all again).
  void add_readings(double t) {
    if (series_dots_.empty() || t < dots_until_) {
      for (View& v : worlds_) {
        v.dots = cv::Mat(v.panel.background.size(), CV_8UC3, cv::Scalar(0, 0, 0));
        v.dots_mask = cv::Mat(v.panel.background.size(), CV_8U, cv::Scalar(0));
      }
      series_dots_ = cv::Mat(size_, CV_8UC3, cv::Scalar(0, 0, 0));
      series_dots_mask_ = cv::Mat(size_, CV_8U, cv::Scalar(0));
      dots_drawn_ = 0;
    }
    dots_until_ = t;
    for (; dots_drawn_ < r_.readings.size() && r_.readings[dots_drawn_].time_s <= t;
         ++dots_drawn_) {
      const ReplayReading& s = r_.readings[dots_drawn_];
      for (View& v : worlds_) {
        const cv::Point p = v.panel.px(seen(v, s.position, s.z));
        cv::circle(v.dots, p, 2, reading_colour(s.value), cv::FILLED);
        cv::circle(v.dots_mask, p, 2, cv::Scalar(255), cv::FILLED);
      }
      const cv::Point q = series_at(s.time_s, s.value);
      cv::circle(series_dots_, q, 1, cv::Scalar(150, 150, 150), cv::FILLED);
      cv::circle(series_dots_mask_, q, 1, cv::Scalar(255), cv::FILLED);
    }
  }

  // The readings over time: stops as dots, readings on the way as small ones, now as a line.
  void draw_series(cv::Mat& image, double t) {
    TextPainter text(0.4, 1);
    const cv::Rect box = series_box();
    cv::rectangle(image, box, cv::Scalar(120, 120, 120), 1);
    text.put(image, "readings over time", {series_.x + 56, series_.y + 4});
    const double end = std::max(r_.ended_s, r_.time_of(r_.frames() - 1));
    auto at = [&](double time, double v) { return series_at(time, v); };
    series_dots_.copyTo(image, series_dots_mask_);
    for (const ReplayStop& s : r_.stops)
      if (s.time_s <= t)
        dot(image, at(s.time_s, s.value), 4, reading_colour(s.value), robot_colour(s.robot));
    auto vertical = [&](double time, const cv::Scalar& colour) {
      const int x = static_cast<int>(std::lround(at(time, 0.0).x));
      cv::line(image, {x, box.y}, {x, box.y + box.height}, colour, 1);
    };
    if (!r_.stopped_by.empty() && t >= r_.declared_s) vertical(r_.declared_s, colours::kEstimate);
    vertical(t, cv::Scalar(40, 40, 200));
    const std::string top = fixed(top_reading_, 0);
    text.put(image, top, {box.x - 6 - text.size(top).width, box.y - 2});
    text.put(image, "0", {box.x - 6 - text.size("0").width, box.y + box.height - 12});
    text.put_vertical(image, "reading (log)", {series_.x + 2, box.y + box.height / 2 - 40});
    text.put(image, "0", {box.x, box.y + box.height + 4});
    const std::string last = fixed(end, 0);
    text.put(image, last, {box.x + box.width - text.size(last).width, box.y + box.height + 4});
    text.put(image, "time [s]",
             {box.x + box.width / 2 - text.size("time [s]").width / 2, box.y + box.height + 4});
  }

  void draw_header(cv::Mat& image, double t) {
    TextPainter text(0.55, 1);
    text.put(image, r_.title, {12, 6});
    std::string status = "t = " + fixed(t, 0) + " s";
    int stops = 0;
    for (const ReplayStop& s : r_.stops)
      stops += s.time_s <= t;
    status += "   stops " + std::to_string(stops);
    const int robot = 0;  // a tracker's distance: the first robot's
    // In the tunnel, distances in 3-D.
    const double source_z = r_.side ? r_.side->source_z : 0.0;
    const auto off = [&](Vec2 p, double z) {
      return std::hypot(norm(p - r_.source), z - source_z);
    };
    if (!r_.has_estimate) {
      const int k = std::min(r_.frames() - 1, static_cast<int>(std::lround(t / r_.every_s)));
      status += "   " + fixed(off(r_.positions[k][robot], robot_z(k, robot)), 2) +
                " m from the source (" + r_.method + " holds no estimate)";
    } else if (const ReplayStop* last = last_stop(t)) {
      const Vec2 e = r_.map.to_frame(last->estimate);
      status += "   estimate (" + fixed(e.x, 2) + ", " + fixed(e.y, 2) +
                (r_.side ? ", " + fixed(last->estimate_z, 2) : "") + "), error " +
                fixed(off(last->estimate, last->estimate_z), 2) + " m";
    }
    if (t >= r_.declared_s - 1e-9 && !r_.stopped_by.empty())
      status += "   stopped (" + r_.stopped_by + ") at " + fixed(r_.declared_s, 0) + " s";
    if (!r_.approach.empty() && t >= r_.declared_s - 1e-9)
      status += t < r_.ended_s ? ", driving to its estimate" : ", at its estimate";
    text.put(image, status, {12, 6 + text.size(r_.title).height + 8});
  }

  const ReplayStop* last_stop(double t) const {
    const ReplayStop* last = nullptr;
    for (const ReplayStop& s : r_.stops)
      if (s.time_s <= t) last = &s;
    return last;
  }

  const Replay& r_;
  cv::Size size_;
  int header_ = 48;
  std::vector<View> worlds_, beliefs_;  // a view each, or the tunnel's from above and the side
  cv::Rect series_;
  cv::Mat gas_, belief_table_;
  double top_reading_ = 1.0;
  // The readings on the way drawn so far (add_readings): up to time dots_until_, the first
  // dots_drawn_ of them.
  cv::Mat series_dots_, series_dots_mask_;
  std::size_t dots_drawn_ = 0;
  double dots_until_ = -1.0;
};

ReplayPainter::ReplayPainter(const Replay& replay, cv::Size size) : replay_(replay), size_(size) {
  if (size.width < 640 || size.height < 360 || size.width % 2 != 0 || size.height % 2 != 0)
    throw std::logic_error("ReplayPainter: frames of even sides, at least 640 x 360");
  panels_ = std::make_unique<Panels>(replay, size);
}

ReplayPainter::~ReplayPainter() = default;

cv::Mat ReplayPainter::frame(int k) {
  if (k < 0 || k >= replay_.frames()) throw std::out_of_range("ReplayPainter: no such frame");
  return panels_->frame(k);
}

AnimationWriter::Written animate_replay(const Replay& replay, const std::filesystem::path& target,
                                        const std::string& flag, const AnimateOptions& options) {
  if (replay.frames() == 0) throw std::logic_error("animate_replay: a replay without frames");
  AnimationWriter writer(target, options.fps, flag);
  ReplayPainter painter(replay, options.size);
  std::optional<ProgressBar> bar;
  if (options.progress) bar.emplace("drawing the replay");
  for (int k = 0; k < replay.frames(); ++k) {
    writer.add(painter.frame(k));
    if (bar) bar->update(static_cast<double>(k + 1) / replay.frames());
  }
  if (bar) bar->finish();
  return writer.finish();
}

void report_animation(const AnimationWriter::Written& w, nlohmann::ordered_json& json,
                      std::string& text) {
  json["animation"] = {{"file", w.file.string()}, {"format", w.format}, {"frames", w.frames}};
  if (!w.note.empty()) json["animation"]["note"] = w.note;
  text += "\nwrote " + w.file.string() + " (" + std::to_string(w.frames) + " frames)" +
          (w.note.empty() ? "" : "; " + w.note);
}

AnimationWriter::Written animate_plume(const Map& map, Vec2 source, const GridShape& grid,
                                       const std::vector<std::vector<float>>& frames,
                                       double every_s, const std::string& title,
                                       const std::filesystem::path& target, const std::string& flag,
                                       const AnimateOptions& options) {
  if (frames.empty()) throw std::logic_error("animate_plume: no frames");
  AnimationWriter writer(target, options.fps, flag);
  Replay scale;  // the replay's log levels
  scale.plume_top = replay_plume_top(frames);
  Map with_source = map;
  with_source.sources = {source};
  const int header = std::max(48, options.size.height / 13);
  const MapPanel panel =
      map_panel(with_source, {options.size.width, options.size.height - header},
                Frame{"gas (log scale, up to " + fixed(scale.plume_top, 0) + " units)",
                      std::nullopt,
                      {},
                      true});
  const cv::Point at((options.size.width - panel.background.cols) / 2, header);
  const cv::Mat gas = colour_table(cv::COLORMAP_INFERNO, true);
  std::vector<std::uint8_t> levels(grid.size());
  for (std::size_t k = 0; k < frames.size(); ++k) {
    for (std::size_t c = 0; c < levels.size(); ++c)
      levels[c] = scale.plume_level(frames[k][c]);
    cv::Mat image(options.size, CV_8UC3, cv::Scalar(255, 255, 255));
    cv::Mat p = panel.background.clone();
    paint_levels(p, panel, levels.data(), grid, gas);
    cross(p, panel.px(source), 6, colours::kSource, 2);
    p.copyTo(image(cv::Rect(at, p.size())));
    TextPainter text(0.55, 1);
    text.put(image, title, {12, 6});
    text.put(image, "t = " + fixed(static_cast<double>(k) * every_s, 0) + " s after the spin-up",
             {12, 6 + text.size(title).height + 8});
    writer.add(image);
  }
  return writer.finish();
}

}  // namespace plumekit::run
