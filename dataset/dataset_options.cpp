// DatasetOptions' table and validate (declared in manifest.hpp, where the struct lives).
#include "cfd/grid_check.hpp"
#include "core/error.hpp"
#include "core/option_check.hpp"
#include "dataset/manifest.hpp"
#include "dataset/option_tables.hpp"

namespace plumekit::dataset {

const OptionTable<DatasetOptions>& dataset_option_table() {
  using O = DatasetOptions;
  static const OptionTable<O> table{
      "Dataset (dataset::DatasetOptions)",
      {{"dataset.maps", "--maps", &O::maps, count_range(1, 1'000'000), "Number of random maps",
        "the thesis's dataset has 180"},
       {"dataset.sources", "--sources", &O::sources, count_range(1, 1'000'000), "Sources per map",
        "the thesis's dataset has 100 per map"},
       {"dataset.source_clearance", "", &O::source_clearance, non_negative(10.0, "m"),
        "Sources keep this far from obstacles, m"},
       {"dataset.feature_cell", "--feature-cell", &O::feature_cell,
        zero_or(real_range(0.02, 2.0, "m")),
        "Feature grid: 0, the thesis's 64 x 64 grid over the arena (3 input channels); else "
        "cells of about this size in m over the whole map, with the wind as 2 more channels "
        "(the v2 surrogate's data; 0.2)",
        "0 (the thesis's 64 x 64 grid) or a cell size; the v2 model uses 0.2 m"},
       {"dataset.physics_input",
        "--physics-input",
        &O::physics_input,
        {},
        "Add the physics plume of each source (steady advection-diffusion in the map's wind) as "
        "an input channel before the source distance: a hybrid model's data (needs "
        "--feature-cell)"}}};
  return table;
}

void DatasetOptions::validate() const {
  const OptionTable<DatasetOptions>& table = dataset_option_table();
  if (given_maps.empty()) {  // given maps bring their own sources
    validate_entry(table.entry("dataset.maps"), *this);
    validate_entry(table.entry("dataset.sources"), *this);
    map.validate();
  }
  if (given_maps.size() != map_files.size())
    throw std::logic_error("DatasetOptions: given_maps and map_files differ in length");
  validate_entry(table.entry("dataset.source_clearance"), *this);
  validate_entry(table.entry("dataset.feature_cell"), *this);
  if (physics_input && !(feature_cell > 0))
    throw OptionError("dataset.physics_input",
                      "needs a physical grid: give --feature-cell too (0.2 m, as the shipped "
                      "models); the thesis's 64 x 64 grid has three channels only");
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
