#pragma once
// The options tables of the simulated world and its filament plume (core/option_table.hpp):
// WorldOptions::validate(), localize's world flags and docs/options.md are made from it.
// world/world_options.cpp.
#include "core/option_table.hpp"

namespace plumekit::world {

struct WorldOptions;
struct FilamentOptions;
struct GasSensorModel;

// Every number and switch of WorldOptions but the filament plume and the gas sensor, which
// check their own. --wind-noise and --position-noise, which also take presets, are bound by hand.
const OptionTable<WorldOptions>& world_option_table();
// Every number of the filament plume; --world, --occlusion and --wind-model set its switches
// (apps/cli.hpp), --filaments-per-second its release. world/filament_model.cpp.
const OptionTable<FilamentOptions>& filament_option_table();
// The gas sensor's response; --gas-sensor sets it from a preset. world/gas_sensor.cpp.
const OptionTable<GasSensorModel>& gas_sensor_option_table();

}  // namespace plumekit::world
