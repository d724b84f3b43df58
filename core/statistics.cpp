#include "core/statistics.hpp"

#include <algorithm>
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

}  // namespace plumekit
