#pragma once
// Where a gas map puts the source (seed 000 §8.5.2.1's six estimates): the peaks of the mean, the
// variance and their product, and the centres of the cells within 90 % of each one's maximum.
#include <string>
#include <vector>

#include "core/geometry.hpp"
#include "methods/kernel_dmv.hpp"

namespace plumekit::methods {

struct SourceEstimate {
  std::string name;  // "peak mean", "peak variance", ..., "90% area mean", ...
  Vec2 position;     // arena frame
  Vec2 lo, hi;       // the 90 % areas' extent (equal to position for the peaks)
};
// The peaks of the mean, the variance and their product, and the centres of the cells within 90 %
// of each one's maximum.
std::vector<SourceEstimate> source_estimates(const GdmMaps& maps);

}  // namespace plumekit::methods
