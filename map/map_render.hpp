#pragma once
// Pictures of maps. MapCanvas lays out an arena on an image (world metres ->
// pixels, y up) and draws its parts; later stages paint fields under the
// obstacles and paths over them with the same transform. The margins around
// the arena are sized from the measured text they hold (title, axis labels,
// colour bar, legend), so a picture reads at any aspect ratio and scale; the
// canvas records every text box it draws, for the layout test.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "core/grid.hpp"
#include "map/map.hpp"

namespace plumekit {

// Options of every map picture.
struct RenderOptions {
  // Pixels per metre of the arena. Pictures are laid out to read from 20 to
  // 400; accepted: 20 .. 1000.
  double px_per_m = 100.0;
  // OptionError naming render.px_per_m when out of range.
  void validate() const;
};

// A drawn picture and the box of every text it holds (image pixels).
struct Picture {
  cv::Mat image;
  std::vector<cv::Rect> text_boxes;
  cv::Rect arena;  // where the arena lies (the first panel's, in a stack)
};

// Writes text onto an image and records each text's box: every picture's
// text goes through one, so the layout test sees all of it.
class TextPainter {
 public:
  TextPainter(double scale, int thickness) : scale_(scale), thickness_(thickness) {}
  double scale() const { return scale_; }
  int thickness() const { return thickness_; }
  // The box a text takes (its descenders included), at this or another scale.
  cv::Size size(const std::string& text) const { return size(text, scale_); }
  cv::Size size(const std::string& text, double scale) const;
  // The text with its box's top-left at `top_left`.
  void put(cv::Mat& image, const std::string& text, cv::Point top_left);
  void put(cv::Mat& image, const std::string& text, cv::Point top_left, double scale);
  // The text on a white box, for labels inside the arena (over a colour map).
  void put_on_white(cv::Mat& image, const std::string& text, cv::Point top_left);
  // Text read bottom to top (a vertical axis label), its box's top-left at top_left.
  void put_vertical(cv::Mat& image, const std::string& text, cv::Point top_left);
  const std::vector<cv::Rect>& boxes() const { return boxes_; }

 private:
  double scale_;
  int thickness_;
  std::vector<cv::Rect> boxes_;
};

// Words of `text` in lines no wider than `width` pixels (a longer word gets its own line).
std::vector<std::string> wrap_words(const TextPainter& painter, const std::string& text, int width,
                                    double scale);

// Axes in metres for a plot area `box` drawn at `px_per_m` whose lower-left corner is the point
// `origin` (m): ticks on the 1-2-5 step that leaves room for their labels, labelled below and
// left of the box, and `x_label` centred under the tick labels and `y_label` upright left of them
// (either may be empty). MapCanvas's axes for pictures of their own layout (the tunnel's panels).
// The room they take outside the box is metre_axes_margins().
void draw_metre_axes(cv::Mat& image, TextPainter& text, const cv::Rect& box, double px_per_m,
                     Vec2 origin, const std::string& x_label, const std::string& y_label);
struct AxesMargins {
  int left = 0;    // tick marks, tick labels and the y label
  int bottom = 0;  // tick marks, tick labels and the x label
};
AxesMargins metre_axes_margins(const TextPainter& text, const cv::Rect& box, double px_per_m,
                               Vec2 origin);

// Pictures one above the other, narrower ones padded white on the right.
Picture stack_pictures(const std::vector<Picture>& pictures);

// Colours are BGR. Each marker kind has its own colour across all pictures.
namespace colours {
const cv::Scalar kInlet(200, 110, 20);
const cv::Scalar kOutlet(40, 150, 40);
const cv::Scalar kObstacle(105, 100, 95);
const cv::Scalar kSource(30, 30, 220);
const cv::Scalar kStart(230, 190, 0);  // cyan: green is the outlet's
const cv::Scalar kGoal(170, 40, 170);
const cv::Scalar kEstimate(200, 40, 200);
const cv::Scalar kPath(170, 60, 20);
}  // namespace colours

// One legend row item: a symbol in a colour and what it stands for.
struct LegendEntry {
  enum class Symbol { Swatch, Dot, Line, Cross, Ring };
  Symbol symbol = Symbol::Swatch;
  cv::Scalar colour;
  std::string text;
};

// A legend: entries in rows no wider than `width` pixels, each a symbol two
// text heights wide and its text; every picture's legend is laid out and
// drawn by these two.
struct LegendLayout {
  std::vector<std::vector<int>> rows;  // entry indices per row
  int widest = 0;                      // the widest entry, pixels
  int row_height = 0;
  int height() const { return static_cast<int>(rows.size()) * row_height; }
};
LegendLayout plan_legend(const TextPainter& text, const std::vector<LegendEntry>& entries,
                         int width);
// The legend with its top-left at `at`.
void draw_legend(cv::Mat& image, TextPainter& text, const std::vector<LegendEntry>& entries,
                 const LegendLayout& layout, cv::Point at);

// A vertical colour bar right of the arena. The label carries the unit,
// e.g. "speed [m/s]".
struct ColourBar {
  double lo = 0.0, hi = 1.0;
  std::string label;
  int colormap = cv::COLORMAP_VIRIDIS;
  // Every value is `lo` (e.g. an all-zero std): the bar says so instead of
  // showing an invented range.
  bool uniform = false;
};

// What a picture puts around its arena; the canvas sizes its margins from it.
struct Frame {
  std::string title;
  std::optional<ColourBar> colour_bar;
  // The map's own entries (inlet, outlet, obstacle, and source when the map
  // has sources) come first unless map_legend is false; then these.
  std::vector<LegendEntry> legend;
  bool map_legend = true;
  // The vertical axis's name: "z [m]" for the tunnel seen from the side.
  std::string y_label = "y [m]";
};

class MapCanvas {
 public:
  MapCanvas(const Map& map, const RenderOptions& options, Frame frame = {});
  explicit MapCanvas(const Map& map, double px_per_m = 100.0)
      : MapCanvas(map, RenderOptions{px_per_m}) {}

  cv::Mat& image() { return image_; }
  const Map& map() const { return map_; }
  double px_per_m() const { return px_per_m_; }
  // Sizes of marks (radii, line widths) grow with the text: 1 at the floor.
  double mark_scale() const { return mark_scale_; }
  // The arena's rectangle in image pixels.
  cv::Rect arena_rect() const;
  // Pixel position of a world point (sub-pixel, for anti-aliased drawing).
  cv::Point2d to_px(Vec2 p) const;
  cv::Point pixel(Vec2 p) const;
  // to_px in OpenCV's fixed point (kFixedShift fractional bits).
  cv::Point fixed(Vec2 p) const;
  static constexpr int kFixedShift = 4;

  void draw_free_space();
  void draw_obstacles();
  void draw_walls_and_openings();
  // The map's sources, labelled S0, S1, ...
  void draw_sources();
  // One source with its label (e.g. "S2"), for pictures of one run.
  void draw_source(Vec2 p, const std::string& label);
  // A filled circle with a white outline, for sources, samples and estimates;
  // the radius is scaled by mark_scale().
  void draw_marker(Vec2 p, const cv::Scalar& colour, int radius_px);
  void draw_cross(Vec2 p, const cv::Scalar& colour);
  // A circle outline (radius scaled by mark_scale()), e.g. where a moved end was asked for.
  void draw_ring(Vec2 p, const cv::Scalar& colour, int radius_px = 5);

  // Paints a cell-centred field over the arena with a colour map (OpenCV's
  // viridis by default), values clamped to [lo, hi]; NaN cells stay unpainted.
  void draw_field(const Grid<double>& field, double lo, double hi,
                  int colormap = cv::COLORMAP_VIRIDIS);
  // A polyline in world coordinates; the thickness is scaled by mark_scale().
  void draw_path(const std::vector<Vec2>& path, const cv::Scalar& colour, int thickness = 1);

  // Axes in metres on both sides, the colour bar, the legend and the title:
  // everything in the margins. Call once, after the arena is drawn.
  Picture finish();

 private:
  void plan_layout();
  void collect_legend();
  void draw_axes();
  void draw_colour_bar(const ColourBar& bar);
  void draw_title();

  Map map_;
  double px_per_m_;
  Frame frame_;
  double font_ = 0.4, mark_scale_ = 1.0;
  int thickness_ = 1;
  TextPainter text_{0.4, 1};
  int text_h_ = 0, gap_ = 0, tick_ = 0;
  double step_x_ = 1.0, step_y_ = 1.0;
  int left_ = 0, top_ = 0, body_h_ = 0, bar_x_ = 0, bar_len_ = 0;
  std::vector<std::string> title_lines_;
  std::vector<LegendEntry> legend_;
  LegendLayout legend_layout_;
  cv::Mat image_;
};

// The map: free space, obstacles, walls, openings, sources, axes and legend.
// cells > 0 also shows the grid of that cell size, tinting the cells that
// count as solid.
Picture render_map(const Map& map, const RenderOptions& options = {}, double cells = 0.0);

// One field over the map (e.g. a plume's mean): the field under the
// obstacles, the source, a colour bar labelled `label` (with its unit).
// NaN cells stay unpainted. from_zero: the scale starts at 0 rather than at
// the smallest value (concentrations). A constant field is said to be so.
struct FieldPanel {
  Grid<double> field;
  std::string title;
  std::string label;
  bool from_zero = false;
};
Picture draw_field_panel(const Map& map, const FieldPanel& panel, Vec2 source,
                         const RenderOptions& options = {80.0});
// Several panels one above the other.
Picture draw_field_panels(const Map& map, const std::vector<FieldPanel>& panels, Vec2 source,
                          const RenderOptions& options = {80.0});

// A plume's picture (`plume`, `predict`): its mean above its std, both
// scaled from zero, obstacle cells unpainted, titled with the map, `model`
// (e.g. "filament plume") and the source; `unit` is the concentration's. An empty
// std (a mean-only model) draws the mean alone.
Picture draw_plume(const Map& map, const Grid<double>& mean, const Grid<double>& std, Vec2 source,
                   const std::string& model, const std::string& unit,
                   const RenderOptions& options = {80.0});
// The same from row-major float arrays on `grid` (row 0 at y = 0).
Picture draw_plume(const Map& map, const GridShape& grid, const std::vector<float>& mean,
                   const std::vector<float>& std, Vec2 source, const std::string& model,
                   const std::string& unit, const RenderOptions& options = {80.0});

// PNG-encode, mark as plumekit's, and write atomically under the output rule
// (output_target.hpp); InputError when the path may not or cannot be written.
void write_png(const cv::Mat& image, const std::filesystem::path& path);
inline void write_png(const Picture& picture, const std::filesystem::path& path) {
  write_png(picture.image, path);
}

}  // namespace plumekit
