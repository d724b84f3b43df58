// The pictures core draws itself: a map (with its grid, optionally) and fields
// over a map (a plume's mean and std, a dataset sample's channels).
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include <opencv2/imgproc.hpp>

#include "core/option_check.hpp"
#include "map/map_render.hpp"
#include "map/rasterize.hpp"

namespace plumekit {

namespace {

const cv::Scalar kSolidCell(60, 60, 230);

// Tints the cells that count as solid at `cell` metres, to show the rasterization rule.
void overlay_solid_cells(MapCanvas& canvas, double cell) {
  const Map& map = canvas.map();
  const GridShape shape = GridShape::with_cell(map.width, map.height, cell);
  const auto solid = rasterize_occupancy(map, shape);
  cv::Mat tint = canvas.image().clone();
  for (int j = 0; j < shape.ny; ++j)
    for (int i = 0; i < shape.nx; ++i) {
      const cv::Point a = canvas.pixel({i * shape.dx(), (j + 1) * shape.dy()});
      const cv::Point b = canvas.pixel({(i + 1) * shape.dx(), j * shape.dy()});
      if (solid(i, j)) cv::rectangle(tint, a, b - cv::Point(1, 1), kSolidCell, cv::FILLED);
      cv::rectangle(tint, a, b, cv::Scalar(200, 200, 200), 1);
    }
  cv::addWeighted(tint, 0.45, canvas.image(), 0.55, 0.0, canvas.image());
}

Map with_source(const Map& map, Vec2 source) {
  Map m = map;
  m.sources = {source};
  return m;
}

}  // namespace

Picture render_map(const Map& map, const RenderOptions& options, double cells) {
  std::ostringstream title;
  title << (map.name.empty() ? "map" : map.name) << "  (" << compact(map.width) << " x "
        << compact(map.height) << " m, " << map.obstacles.size()
        << (map.obstacles.size() == 1 ? " obstacle" : " obstacles");
  Frame frame;
  if (cells > 0.0) {
    title << ", grid of " << compact(cells) << " m cells";
    // The tint is blended at 45 %: the swatch shows it over free space.
    frame.legend.push_back({LegendEntry::Symbol::Swatch, cv::Scalar(163, 162, 238),
                            "solid cell at " + compact(cells) + " m"});
  }
  title << ")";
  frame.title = title.str();
  if (!map.starts.empty())
    frame.legend.push_back({LegendEntry::Symbol::Ring, colours::kStart, "robot start"});
  MapCanvas canvas(map, options, frame);
  canvas.draw_free_space();
  canvas.draw_obstacles();
  // The grid tint goes over the obstacles and under the walls and sources.
  if (cells > 0.0) overlay_solid_cells(canvas, cells);
  canvas.draw_walls_and_openings();
  canvas.draw_sources();
  for (Vec2 p : map.starts)
    canvas.draw_ring(p, colours::kStart, 8);
  return canvas.finish();
}

Picture draw_field_panel(const Map& map, const FieldPanel& panel, Vec2 source,
                         const RenderOptions& options) {
  double lo = HUGE_VAL, hi = -HUGE_VAL;
  for (double v : panel.field.values)
    if (!std::isnan(v)) lo = std::min(lo, v), hi = std::max(hi, v);
  if (panel.from_zero) lo = 0.0;
  if (!std::isfinite(lo)) lo = 0.0;
  ColourBar bar{lo, hi, panel.label};
  bar.uniform = !(hi > lo);
  MapCanvas canvas(with_source(map, source), options, Frame{panel.title, bar, {}, true});
  canvas.draw_free_space();
  canvas.draw_field(panel.field, lo, bar.uniform ? lo + 1.0 : hi);
  canvas.draw_obstacles();
  canvas.draw_walls_and_openings();
  canvas.draw_marker(source, colours::kSource, 5);
  return canvas.finish();
}

Picture draw_field_panels(const Map& map, const std::vector<FieldPanel>& panels, Vec2 source,
                          const RenderOptions& options) {
  std::vector<Picture> pictures;
  for (const FieldPanel& p : panels)
    pictures.push_back(draw_field_panel(map, p, source, options));
  return stack_pictures(pictures);
}

namespace {

// `values` with the cells whose centre lies in an obstacle set to NaN (unpainted).
Grid<double> free_cells(const Map& map, Grid<double> values) {
  const GridShape& g = values.shape;
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i)
      if (map.obstacle_at(g.centre(i, j)) >= 0) values(i, j) = std::nan("");
  return values;
}

double largest(const Grid<double>& g) {
  double m = 0.0;
  for (double v : g.values)
    if (!std::isnan(v)) m = std::max(m, v);
  return m;
}

}  // namespace

Picture draw_plume(const Map& map, const Grid<double>& mean, const Grid<double>& std, Vec2 source,
                   const std::string& model, const std::string& unit,
                   const RenderOptions& options) {
  std::ostringstream heading;
  heading << (map.name.empty() ? "map" : map.name) << ": " << model << ", source (" << std::fixed
          << std::setprecision(2) << map.frame.to_frame(source).x << ", "
          << map.frame.to_frame(source).y << ")";  // the axes are in the map frame
  const std::string u = unit.empty() ? "concentration units" : unit;
  FieldPanel m{free_cells(map, mean), "", "mean [" + u + "]", true};
  m.title = heading.str() + ": mean concentration, peak " + compact(largest(m.field));
  if (std.values.empty()) return draw_field_panel(map, m, source, options);  // a mean-only model
  FieldPanel s{free_cells(map, std), "", "std [" + u + "]", true};
  const double std_max = largest(s.field);
  s.title = heading.str() + ": std of the concentration, " +
            (std_max > 0.0 ? "largest " + compact(std_max) : "all zero");
  return draw_field_panels(map, {m, s}, source, options);
}

Picture draw_plume(const Map& map, const GridShape& grid, const std::vector<float>& mean,
                   const std::vector<float>& std, Vec2 source, const std::string& model,
                   const std::string& unit, const RenderOptions& options) {
  Grid<double> m(grid, 0.0), s;
  std::copy(mean.begin(), mean.end(), m.values.begin());
  if (!std.empty()) {
    s = Grid<double>(grid, 0.0);
    std::copy(std.begin(), std.end(), s.values.begin());
  }
  return draw_plume(map, m, s, source, model, unit, options);
}

Picture stack_pictures(const std::vector<Picture>& pictures) {
  int width = 0;
  for (const Picture& p : pictures)
    width = std::max(width, p.image.cols);
  Picture out;
  std::vector<cv::Mat> rows;
  int y = 0;
  for (const Picture& p : pictures) {
    cv::Mat padded;
    cv::copyMakeBorder(p.image, padded, 0, 0, 0, width - p.image.cols, cv::BORDER_CONSTANT,
                       cv::Scalar(255, 255, 255));
    rows.push_back(padded);
    for (const cv::Rect& r : p.text_boxes)
      out.text_boxes.push_back(r + cv::Point(0, y));
    y += p.image.rows;
  }
  if (!rows.empty()) cv::vconcat(rows, out.image);
  if (!pictures.empty()) out.arena = pictures.front().arena;
  return out;
}

}  // namespace plumekit
