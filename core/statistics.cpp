#include "core/statistics.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace plumekit {

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

double percentile(std::vector<double> values, double q) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  q = std::clamp(q, 0.0, 1.0);
  const double rank = q * static_cast<double>(values.size() - 1);
  const auto i = static_cast<std::size_t>(rank);
  const double f = rank - static_cast<double>(i);
  return i + 1 < values.size() ? values[i] * (1 - f) + values[i + 1] * f : values[i];
}

Interval wilson_interval(int successes, int n, double z) {
  if (n <= 0) return {};
  const double nn = n, p = successes / nn, z2n = z * z / nn;
  const double centre = (p + 0.5 * z2n) / (1.0 + z2n);
  const double half = z / (1.0 + z2n) * std::sqrt(p * (1.0 - p) / nn + 0.25 * z2n / nn);
  // At 0 and n the bound is exactly 0 or 1; say so rather than trust the rounding.
  return {successes <= 0 ? 0.0 : std::max(0.0, centre - half),
          successes >= n ? 1.0 : std::min(1.0, centre + half)};
}

}  // namespace plumekit
