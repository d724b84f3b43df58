#include "ste/forward_model.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace plumekit::ste {

double ForwardModel::predict_at(const double* params, Vec2 p) const {
  return predict(std::vector<double>(params, params + parameters().size()), {p})[0];
}

std::vector<double> SourceTableModel::predict(const std::vector<double>& params,
                                              const std::vector<Vec2>& points) const {
  const int k = nearest_allowed({params.at(0), params.at(1)});
  const double scale = params.size() > 2 ? params[2] : 1.0;
  std::vector<double> out(points.size(), 0.0);
  if (k < 0) return out;
  for (std::size_t i = 0; i < points.size(); ++i)
    out[i] = scale * readings_at(points[i])[k];
  return out;
}

int SourceTableModel::nearest_allowed(Vec2 p) const {
  const GridShape& g = candidates();
  const std::vector<std::uint8_t>& ok = allowed();
  const int ci = std::clamp(static_cast<int>(p.x / g.dx()), 0, g.nx - 1);
  const int cj = std::clamp(static_cast<int>(p.y / g.dy()), 0, g.ny - 1);
  if (ok[g.index(ci, cj)]) return static_cast<int>(g.index(ci, cj));
  int best = -1;
  double best_d = std::numeric_limits<double>::infinity();
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i)
      if (ok[g.index(i, j)]) {
        const double d = norm(g.centre(i, j) - p);
        if (d < best_d) best_d = d, best = static_cast<int>(g.index(i, j));
      }
  return best;
}

std::vector<std::uint8_t> free_cells(const Map& map, const GridShape& shape, double clearance) {
  std::vector<std::uint8_t> ok(shape.size(), 0);
  for (int j = 0; j < shape.ny; ++j)
    for (int i = 0; i < shape.nx; ++i) {
      const Vec2 c = shape.centre(i, j);
      if (!map.is_free(c)) continue;
      bool clear = std::min({c.x, c.y, map.width - c.x, map.height - c.y}) >= clearance;
      for (const Polygon& poly : map.obstacles)
        for (std::size_t k = 0; clear && k < poly.size(); ++k)
          if (distance_to_segment(c, poly[k], poly[(k + 1) % poly.size()]) < clearance)
            clear = false;
      ok[shape.index(i, j)] = clear;
    }
  return ok;
}

}  // namespace plumekit::ste
