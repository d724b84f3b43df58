#include "ste/stop_rule.hpp"

#include <algorithm>
#include <cmath>

namespace plumekit::ste {

std::string stop_reason(const Posterior& posterior, int samples, const StopOptions& stop) {
  if (posterior.entropy < stop.entropy_fraction * posterior.max_entropy &&
      posterior.seen_mass >= stop.seen_mass)
    return "entropy";
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
