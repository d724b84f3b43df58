#pragma once
// The options table of the random maps (core/option_table.hpp): RandomMapOptions' checks, the
// flags of `maps random` and docs/options.md. dataset/random_maps.cpp.
#include "core/option_table.hpp"

namespace plumekit::dataset {

struct RandomMapOptions;

// Every number of RandomMapOptions; its families (a list) are checked and bound apart.
const OptionTable<RandomMapOptions>& random_map_option_table();

}  // namespace plumekit::dataset
