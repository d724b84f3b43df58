#pragma once
// The options table of the simulated world (core/option_table.hpp): WorldOptions::validate(),
// localize's world flags and docs/options.md are made from it. world/world_options.cpp.
#include "core/option_table.hpp"

namespace plumekit::world {

struct WorldOptions;

// Every number and switch of WorldOptions but the filament plume and the gas sensor, which
// check their own. --wind-noise and --position-noise, which also take presets, are bound by hand.
const OptionTable<WorldOptions>& world_option_table();

}  // namespace plumekit::world
