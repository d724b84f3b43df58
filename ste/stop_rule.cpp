#include "ste/stop_rule.hpp"

#include <algorithm>
#include <cmath>

namespace plumekit::ste {

double mass_within(const Posterior& posterior, double radius) {
  const GridShape& g = posterior.marginal.shape;
  const Vec2 e = posterior.expected_source();
  double mass = 0.0;
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i)
      if (norm(g.centre(i, j) - e) <= radius) mass += posterior.marginal(i, j);
  return mass;
}

std::string stop_reason(const Posterior& posterior, int samples, const StopOptions& stop) {
  const bool seen = posterior.seen_mass >= stop.seen_mass;
  if (seen && posterior.entropy < stop.entropy_fraction * posterior.max_entropy) return "entropy";
  if (seen && stop.confidence_radius > 0.0 &&
      mass_within(posterior, stop.confidence_radius) >= stop.confidence_mass)
    return "confident";
  return samples >= stop.max_samples_in_use() ? "max_samples" : "";
}

int resolve_max_samples(int max_samples, std::size_t floor_goals, double floor_spacing) {
  if (max_samples != StopOptions::kAutoMaxSamples) return max_samples;
  constexpr double kSquareMetresPerSample = 10.0;
  const double area = static_cast<double>(floor_goals) * floor_spacing * floor_spacing;
  return std::max(StopOptions::kThesisMaxSamples,
                  static_cast<int>(std::ceil(area / kSquareMetresPerSample)));
}

}  // namespace plumekit::ste
