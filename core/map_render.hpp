#pragma once
// Pictures of maps. MapCanvas lays out an arena on an image (world metres ->
// pixels, y up) and draws its parts; later stages paint fields under the
// obstacles and paths over them with the same transform.
#include <filesystem>
#include <string>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "core/grid.hpp"
#include "core/map.hpp"

namespace plumekit {

class MapCanvas {
 public:
  explicit MapCanvas(const Map& map, double px_per_m = 100.0);

  cv::Mat& image() { return image_; }
  const Map& map() const { return map_; }
  double px_per_m() const { return px_per_m_; }
  // Pixel position of a world point (sub-pixel, for anti-aliased drawing).
  cv::Point2d to_px(Vec2 p) const;
  cv::Point pixel(Vec2 p) const;

  void draw_free_space();
  void draw_obstacles();
  void draw_walls_and_openings();
  void draw_sources();
  void draw_axes_and_scale();
  void draw_title(const std::string& title);
  // A filled circle with an outline, for sources, samples and estimates.
  void draw_marker(Vec2 p, const cv::Scalar& colour, int radius_px);

  // The whole map: free space, obstacles, walls, openings, sources, scale.
  void draw_map();

  // Paints a cell-centred field over the arena with a colour map (OpenCV's
  // viridis by default), values clamped to [lo, hi]; NaN cells stay unpainted.
  void draw_field(const Grid<double>& field, double lo, double hi,
                  int colormap = cv::COLORMAP_VIRIDIS);
  // A vertical colour bar right of the arena, labelled lo .. hi and `label`.
  void draw_colour_bar(double lo, double hi, const std::string& label,
                       int colormap = cv::COLORMAP_VIRIDIS);
  // A polyline in world coordinates.
  void draw_path(const std::vector<Vec2>& path, const cv::Scalar& colour, int thickness = 1);

 private:
  Map map_;
  double px_per_m_;
  int left_, top_, right_;  // margins in pixels
  cv::Mat image_;
};

// PNG-encode, mark as plumekit's, and write atomically under the output rule
// (output_target.hpp); InputError when the path may not or cannot be written.
void write_png(const cv::Mat& image, const std::filesystem::path& path);

}  // namespace plumekit
