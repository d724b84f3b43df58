#pragma once
// Order statistics with one definition each, for every stage's summaries and pictures,
// and the interval every success rate is quoted with.
#include <vector>

namespace plumekit {

// The middle value; the mean of the two middle values for an even count; 0 when empty.
double median(std::vector<double> values);

// The q-quantile (q in [0, 1]) by linear interpolation between the order statistics
// at rank q (n - 1); 0 when empty. percentile(v, 0.5) == median(v).
double percentile(std::vector<double> values, double q);

// The Wilson score interval of a binomial proportion, successes out of n
// (Wilson 1927), at the normal quantile z (1.96: 95 %). Unlike p +- z sqrt(p
// (1 - p) / n) it stays inside [0, 1] and does not collapse to a point at 0 % or
// 100 %. n = 0 gives [0, 1].
struct Interval {
  double lo = 0.0, hi = 1.0;
};
Interval wilson_interval(int successes, int n, double z = 1.96);

}  // namespace plumekit
