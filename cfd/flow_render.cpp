#include "cfd/flow_render.hpp"

#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "map/map_render.hpp"

namespace plumekit::cfd {

namespace {

const cv::Scalar kStreamline(255, 255, 255);

// Streamlines through evenly spaced seeds, stopped where they run into a
// stretch of the arena another streamline already crossed, so the picture
// stays legible (a simplified Jobard-Lefer placement).
std::vector<std::vector<Vec2>> streamlines(const WindField& wind, double spacing) {
  const GridShape& g = wind.shape();
  const double vmax = std::max(wind.max_speed(), 1e-12);
  const double step = 0.4 * std::min(g.dx(), g.dy());
  const int bins_x = std::max(1, static_cast<int>(g.width / spacing));
  const int bins_y = std::max(1, static_cast<int>(g.height / spacing));
  std::vector<int> owner(static_cast<std::size_t>(bins_x) * bins_y, -1);
  std::vector<int> visited_at(owner.size(), 0);  // step at which the current line entered
  auto bin = [&](Vec2 p) {
    const int i = std::min(bins_x - 1, std::max(0, static_cast<int>(p.x / g.width * bins_x)));
    const int j = std::min(bins_y - 1, std::max(0, static_cast<int>(p.y / g.height * bins_y)));
    return static_cast<std::size_t>(j) * bins_x + i;
  };
  std::vector<std::vector<Vec2>> lines;
  auto trace = [&](Vec2 seed, double direction, int id) {
    std::vector<Vec2> pts{seed};
    Vec2 p = seed;
    for (int k = 0; k < 4000; ++k) {
      const Vec2 v1 = wind.at(p);
      const double s1 = norm(v1);
      if (s1 < 1e-3 * vmax) break;
      const Vec2 mid = p + (0.5 * step * direction / s1) * v1;  // midpoint rule, unit speed
      const Vec2 v2 = wind.at(mid);
      const double s2 = norm(v2);
      if (s2 < 1e-3 * vmax) break;
      const Vec2 next = p + (step * direction / s2) * v2;
      if (next.x < 0 || next.y < 0 || next.x > g.width || next.y > g.height) break;
      const std::size_t b = bin(next);
      if (owner[b] >= 0 && owner[b] != id) break;
      // Back in a bin it left long ago: a closed orbit, drawn once is enough.
      if (owner[b] == id && bin(p) != b && visited_at[b] < k - 4) break;
      if (owner[b] != id || bin(p) != b) visited_at[b] = k;
      owner[b] = id;
      pts.push_back(next);
      p = next;
    }
    return pts;
  };
  int id = 0;
  for (double y = 0.5 * spacing; y < g.height; y += spacing) {
    for (double x = 0.5 * spacing; x < g.width; x += spacing) {
      const Vec2 seed{x, y};
      if (owner[bin(seed)] >= 0 || norm(wind.at(seed)) < 1e-3 * vmax) continue;
      owner[bin(seed)] = id;
      std::vector<Vec2> back = trace(seed, -1.0, id), ahead = trace(seed, 1.0, id);
      std::vector<Vec2> line(back.rbegin(), back.rend());
      line.insert(line.end(), ahead.begin() + 1, ahead.end());
      if (line.size() > 4) lines.push_back(std::move(line));
      ++id;
    }
  }
  return lines;
}

}  // namespace

Picture draw_wind(const Map& map, const WindField& wind, const RenderOptions& options) {
  const GridShape& g = wind.shape();
  Grid<double> speed(g, std::numeric_limits<double>::quiet_NaN());
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i)
      if (!wind.solid(i, j)) speed(i, j) = norm(wind.cell_velocity(i, j));
  const double vmax = wind.max_speed();
  std::ostringstream title;
  title << (map.name.empty() ? "map" : map.name) << ": wind speed and streamlines  (" << g.nx
        << " x " << g.ny << " cells, max " << std::setprecision(3) << vmax << " m/s)";
  ColourBar bar{0.0, vmax, "speed [m/s]"};
  bar.uniform = !(vmax > 0.0);
  Frame frame{title.str(), bar, {{LegendEntry::Symbol::Line, kStreamline, "streamline"}}, true};
  MapCanvas canvas(map, options, frame);
  canvas.draw_free_space();
  canvas.draw_field(speed, 0.0, vmax);
  canvas.draw_obstacles();
  for (const auto& line : streamlines(wind, 0.25)) {
    canvas.draw_path(line, kStreamline, 1);
    // An arrowhead halfway along shows the direction.
    const std::size_t m = line.size() / 2;
    const Vec2 a = line[m - 1], b = line[m];
    const Vec2 d = (1.0 / std::max(norm(b - a), 1e-12)) * (b - a);
    const cv::Point tip = canvas.pixel(b);
    const Vec2 left{-d.x * 0.7 - d.y * 0.5, -d.y * 0.7 + d.x * 0.5};
    const Vec2 right{-d.x * 0.7 + d.y * 0.5, -d.y * 0.7 - d.x * 0.5};
    const double len = 6.0 * canvas.mark_scale();  // pixels
    const int width = std::max(1, static_cast<int>(std::lround(canvas.mark_scale())));
    for (Vec2 side : {left, right})
      cv::line(canvas.image(), tip,
               tip + cv::Point(static_cast<int>(len * side.x), static_cast<int>(-len * side.y)),
               kStreamline, width, cv::LINE_AA);
  }
  canvas.draw_walls_and_openings();
  canvas.draw_sources();
  return canvas.finish();
}

cv::Mat render_wind(const Map& map, const WindField& wind, double px_per_m) {
  return draw_wind(map, wind, RenderOptions{px_per_m}).image;
}

}  // namespace plumekit::cfd
