#include "gdm/map_score.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/resample.hpp"
#include "dataset/advection_diffusion.hpp"
#include "dataset/plume.hpp"

namespace plumekit::gdm {

Grid<double> true_mean_plume(const Map& map, const cfd::WindField& wind, Vec2 source,
                             const GridShape& cells) {
  dataset::check_source(map, source);
  const dataset::AdvectionDiffusion ad(wind, dataset::filament_world_mean());
  const GridResampler resample(ad.shape(), ad.solid_mask(), cells);
  Grid<double> truth = resample.apply(ad.solve(source));
  for (int j = 0; j < cells.ny; ++j)
    for (int i = 0; i < cells.nx; ++i)
      if (map.obstacle_at(cells.centre(i, j)) >= 0) truth(i, j) = std::nan("");
  return truth;
}

MapScore score_mean(const Grid<double>& mean, const Grid<double>& truth) {
  std::vector<double> p, q;
  MapScore s;
  double sq = 0.0;
  for (std::size_t c = 0; c < mean.values.size(); ++c) {
    const double a = mean.values[c], b = truth.values.at(c);
    if (!std::isfinite(a) || !std::isfinite(b)) continue;
    p.push_back(std::max(a, 0.0));
    q.push_back(std::max(b, 0.0));
    sq += (a - b) * (a - b);
    s.truth_peak = std::max(s.truth_peak, b);
  }
  if (p.empty()) return s;
  s.rmse = std::sqrt(sq / p.size());
  // Sums to 1 with every cell at least 1e-9 (a map with no gas at all: uniform).
  const auto to_distribution = [](std::vector<double>& v) {
    double sum = 0.0;
    for (double x : v)
      sum += x;
    const double floor = 1e-9, share = 1.0 - floor * static_cast<double>(v.size());
    for (double& x : v)
      x = sum > 0.0 ? floor + share * x / sum : 1.0 / static_cast<double>(v.size());
  };
  to_distribution(p);
  to_distribution(q);
  double kl_pq = 0.0, kl_qp = 0.0;
  for (std::size_t c = 0; c < p.size(); ++c) {
    kl_pq += p[c] * std::log(p[c] / q[c]);
    kl_qp += q[c] * std::log(q[c] / p[c]);
  }
  s.kl_distance = 0.5 * (kl_pq + kl_qp);
  return s;
}

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

}  // namespace plumekit::gdm
