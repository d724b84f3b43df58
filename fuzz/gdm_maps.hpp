#pragma once
// What the two gas-map readers' targets (fuzz_gdm_samples, fuzz_gdm_run) do with accepted samples:
// read them on the same arena and check that Kernel DM+V/W's maps are finite in every cell.
#include <cmath>
#include <cstdlib>
#include <vector>

#include "map/map.hpp"
#include "methods/kernel_dmv.hpp"

namespace plumekit::fuzz {

// The arena both targets read samples on: 10 x 4 m, its origin off (0, 0).
inline Map gdm_arena() {
  Map map = default_arena(10.0, 4.0);
  map.frame.origin = {-1.0, 2.0};
  return map;
}

// Aborts when a cell of the mean, variance, confidence or weight map is not finite.
inline void check_finite_gdm_maps(const Map& map, const std::vector<methods::Sample>& samples) {
  methods::GdmOptions o;
  o.cell = 0.5;  // 20 x 8 cells: quick
  o.wind_stretch = 0.6;
  const methods::GdmMaps m = methods::kernel_dmv(map, samples, o);
  for (const auto* g : {&m.mean, &m.variance, &m.confidence, &m.weight})
    for (double v : g->values)
      if (!std::isfinite(v)) std::abort();
}

}  // namespace plumekit::fuzz
