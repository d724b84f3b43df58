#pragma once
// The median of a sample (the mean of the middle two for an even count; 0 when
// empty), shared by the benchmarks that report medians of repeated runs.
#include <algorithm>
#include <vector>

inline double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}
