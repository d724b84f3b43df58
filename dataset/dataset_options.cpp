// DatasetOptions::validate (declared in manifest.hpp, where the struct lives).
#include "cfd/grid_check.hpp"
#include "core/error.hpp"
#include "core/option_check.hpp"
#include "dataset/manifest.hpp"

namespace plumekit::dataset {

void DatasetOptions::validate() const {
  if (given_maps.empty()) {
    check_count("dataset.maps", maps, 1, 1'000'000, "the thesis's dataset has 180");
    check_count("dataset.sources", sources, 1, 1'000'000, "the thesis's dataset has 100 per map");
    map.validate();
  }
  if (given_maps.size() != map_files.size())
    throw std::logic_error("DatasetOptions: given_maps and map_files differ in length");
  check_non_negative("dataset.source_clearance", source_clearance, 10.0, "m",
                     "the default is 0.1 m");
  if (feature_cell != 0.0)
    check_range("dataset.feature_cell", feature_cell, 0.02, 2.0, "m",
                "0 (the thesis's 64 x 64 grid) or a cell size; the v2 model uses 0.2 m");
  if (inlet_speed_hi != 0.0 || inlet_speed_lo != 0.0) {
    const std::string advice = "LO,HI with 0 < LO <= HI, each " + std::string(kInletSpeedBound) +
                               "; unset, maps.inlet_speed";
    for (const double speed : {inlet_speed_lo, inlet_speed_hi})
      check_range("dataset.inlet_speeds", speed, 0.01, kMaxInletSpeed, "m/s", advice);
    if (inlet_speed_hi < inlet_speed_lo)
      throw OptionError("dataset.inlet_speeds", "LO must not exceed HI, got LO " +
                                                    compact(inlet_speed_lo) + " and HI " +
                                                    compact(inlet_speed_hi) + " m/s; " + advice);
    if (!given_maps.empty())
      throw OptionError("dataset.inlet_speeds",
                        "draws the speed of random maps; given maps keep their own");
  }
  flow.validate();
  plume.validate();
  // Each map's flow grid (cell count and memory) before any is solved: a
  // random map's arena is maps.width x maps.height.
  if (given_maps.empty()) {
    cfd::check_grid_size(default_arena(map.width, map.height), flow);
  } else {
    for (std::size_t k = 0; k < given_maps.size(); ++k) {
      if (given_maps[k].sources.empty())
        throw InputError(map_files[k] + ": the map has no sources; a dataset needs them");
      try {
        cfd::check_grid_size(given_maps[k], flow);
      } catch (const OptionError& e) {
        throw OptionError(e.field(), e.message() + " (map " + map_files[k] + ")");
      }
    }
  }
}

}  // namespace plumekit::dataset
