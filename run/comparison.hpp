#pragma once
// Several methods evaluated on the same runs (`evaluate --method a,b,...`), side by side: one row
// per method, from its summary and its own time, as the README's "Localization methods compared"
// table (comparison.md), as CSV (comparison.csv) and as JSON rows.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace plumekit::run {

struct MethodRow {
  nlohmann::ordered_json summary;  // as summary.json holds it
  double median_step_s = 0.0;      // its median decision step
  double model_build_s = 0.0;      // its own time: the plume model's build ...
  double decisions_s = 0.0;        // ... and its decisions, summed over its runs
};

struct Comparison {
  std::string markdown, csv;
  nlohmann::ordered_json rows;  // one object per method
};

Comparison compare_methods(const std::vector<MethodRow>& methods);

}  // namespace plumekit::run
