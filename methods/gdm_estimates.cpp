#include "methods/gdm_estimates.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace plumekit::methods {

namespace {

// The peak of `field` and the centre and extent of the cells within 90 % of it.
void estimates_of(const Grid<double>& field, const std::string& what,
                  std::vector<SourceEstimate>& out) {
  const GridShape& g = field.shape;
  double top = -std::numeric_limits<double>::infinity();
  Vec2 peak;
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i)
      if (std::isfinite(field(i, j)) && field(i, j) > top) top = field(i, j), peak = g.centre(i, j);
  out.push_back({"peak " + what, peak, peak, peak});
  SourceEstimate area{"90% area " + what, {0, 0}, peak, peak};
  int n = 0;
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i)
      if (std::isfinite(field(i, j)) && field(i, j) >= 0.9 * top) {
        const Vec2 c = g.centre(i, j);
        area.position = area.position + c;
        area.lo = {std::min(area.lo.x, c.x), std::min(area.lo.y, c.y)};
        area.hi = {std::max(area.hi.x, c.x), std::max(area.hi.y, c.y)};
        ++n;
      }
  area.position = n > 0 ? (1.0 / n) * area.position : peak;
  out.push_back(area);
}

}  // namespace

std::vector<SourceEstimate> source_estimates(const GdmMaps& maps) {
  Grid<double> product = maps.mean;
  for (std::size_t c = 0; c < product.values.size(); ++c)
    product.values[c] *= maps.variance.values[c];
  std::vector<SourceEstimate> out;
  estimates_of(maps.mean, "mean", out);
  estimates_of(maps.variance, "variance", out);
  estimates_of(product, "mean x variance", out);
  // Peaks first, then the areas, as the seed lists them (A-C, D-F).
  std::stable_partition(out.begin(), out.end(),
                        [](const SourceEstimate& e) { return e.name.rfind("peak", 0) == 0; });
  return out;
}

}  // namespace plumekit::methods
