#include "ste/navigation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.hpp"

namespace plumekit::ste {

Navigator::Navigator(const planner::FreeSpace& space, const GridShape& bins,
                     const NavigationOptions& options)
    : space_(space), bins_(bins), options_(options), region_(bins.size(), -1) {
  options.validate();
  for (int j = 0; j < bins.ny; ++j)
    for (int i = 0; i < bins.nx; ++i)
      region_[bins.index(i, j)] = space.region_of(bins.centre(i, j));
}

Decision Navigator::decide(Vec2 robot, const Estimator& estimator,
                           const Posterior& posterior) const {
  Decision d;
  const int home = space_.region_of(robot);
  // V_KLD: the most informative reachable candidate.
  double best = -1.0;
  d.kld_target = robot;
  const int n = options_.lattice;
  for (int dj = -n; dj <= n; ++dj)
    for (int di = -n; di <= n; ++di) {
      if (di == 0 && dj == 0) continue;
      const Vec2 c{robot.x + di * options_.step, robot.y + dj * options_.step};
      if (!space_.contains(c) || space_.region_of(c) != home) continue;
      const double g = options_.reward == NavigationOptions::Reward::Kl
                           ? estimator.information_gain(c, posterior)
                           : estimator.expected_information_gain(c, posterior);
      d.candidates.push_back(c);
      d.gains.push_back(g);
      if (g > best) best = g, d.kld_target = c;
    }

  // V_source: the MAP, or the best of beta P_M + (1 - beta) D_I.
  d.source_target = posterior.map;
  if (options_.enhanced) {
    const GridShape& g = bins_;
    // P_M on the bins.
    std::vector<double> pm(g.size(), 0.0);
    const GridShape& m = posterior.marginal.shape;
    for (int j = 0; j < m.ny; ++j)
      for (int i = 0; i < m.nx; ++i) {
        const Vec2 c = m.centre(i, j);
        pm[g.index(std::clamp(static_cast<int>(c.x / g.dx()), 0, g.nx - 1),
                   std::clamp(static_cast<int>(c.y / g.dy()), 0, g.ny - 1))] +=
            posterior.marginal(i, j);
      }
    std::vector<double> inv(g.size(), 0.0);
    double inv_sum = 0.0;
    const int ri = static_cast<int>(robot.x / g.dx()), rj = static_cast<int>(robot.y / g.dy());
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) {
        const std::size_t k = g.index(i, j);
        if (region_[k] != home || (i == ri && j == rj)) continue;
        inv[k] = 1.0 / std::max(1e-9, norm(g.centre(i, j) - robot));
        inv_sum += inv[k];
      }
    double top = -1.0;
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) {
        const std::size_t k = g.index(i, j);
        if (region_[k] != home) continue;
        const double v = options_.beta * pm[k] +
                         (1.0 - options_.beta) * (inv_sum > 0.0 ? inv[k] / inv_sum : 0.0);
        if (v > top) top = v, d.source_target = g.centre(i, j);
      }
  }

  const double a = options_.alpha;
  Vec2 goal = robot + a * (d.kld_target - robot) + (1.0 - a) * (d.source_target - robot);
  if (!space_.contains(goal)) goal = space_.nearest_free(goal);
  if (space_.region_of(goal) != home) goal = d.candidates.empty() ? robot : d.kld_target;
  d.goal = goal;
  return d;
}

}  // namespace plumekit::ste
