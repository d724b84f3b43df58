#pragma once
// Order statistics with one definition each, for every stage's summaries and pictures.
#include <vector>

namespace plumekit {

// The middle value; the mean of the two middle values for an even count; 0 when empty.
double median(std::vector<double> values);

// The q-quantile (q in [0, 1]) by linear interpolation between the order statistics
// at rank q (n - 1); 0 when empty. percentile(v, 0.5) == median(v).
double percentile(std::vector<double> values, double q);

}  // namespace plumekit
