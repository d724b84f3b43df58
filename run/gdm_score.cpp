#include "run/gdm_score.hpp"

#include <algorithm>
#include <cmath>

#include "cfd/advection_diffusion.hpp"
#include "core/resample.hpp"
#include "dataset/plume.hpp"

namespace plumekit::run {

Grid<double> true_mean_plume(const Map& map, const cfd::WindField& wind, Vec2 source,
                             const GridShape& cells) {
  dataset::check_source(map, source);
  const cfd::AdvectionDiffusion ad(wind, dataset::filament_world_mean());
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

}  // namespace plumekit::run
