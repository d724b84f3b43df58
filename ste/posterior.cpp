#include "ste/posterior.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.hpp"

namespace plumekit::ste {

GridShape make_bins(const Map& map, const BinOptions& b) {
  b.validate();
  return GridShape{std::max(1, static_cast<int>(std::lround(map.width / b.x))),
                   std::max(1, static_cast<int>(std::lround(map.height / b.y))), map.width,
                   map.height};
}

void check_weight(double weight) {
  if (!(weight > 0.0 && weight <= 1.0))
    throw InputError("ste.sample.weight: " + std::to_string(weight) +
                     " is not a share of a stop's sample (0 < weight <= 1)");
}

double entropy_on_bins(const Grid<double>& marginal, const GridShape& bins) {
  std::vector<double> mass(bins.size(), 0.0);
  const GridShape& g = marginal.shape;
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      const double w = marginal(i, j);
      if (w <= 0.0) continue;
      const Vec2 c = g.centre(i, j);
      const int bi = std::clamp(static_cast<int>(c.x / bins.dx()), 0, bins.nx - 1);
      const int bj = std::clamp(static_cast<int>(c.y / bins.dy()), 0, bins.ny - 1);
      mass[bins.index(bi, bj)] += w;
    }
  double h = 0.0;
  for (double m : mass)
    if (m > 0.0) h -= m * std::log(m);
  return std::max(0.0, h);
}

}  // namespace plumekit::ste
