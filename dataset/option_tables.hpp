#pragma once
// The options tables of the random maps and of a dataset (core/option_table.hpp): RandomMapOptions'
// checks, the flags of `maps random` and docs/options.md. dataset/random_maps.cpp.
#include "core/option_table.hpp"

namespace plumekit::dataset {

struct RandomMapOptions;
struct DatasetOptions;
struct MapSetOptions;

// Every number of RandomMapOptions; its families (a list) are checked and bound apart.
const OptionTable<RandomMapOptions>& random_map_option_table();
// The counts and cells of a dataset; its seed, its inlet speeds (a pair), and the options it
// nests are checked and bound apart. dataset/dataset_options.cpp.
const OptionTable<DatasetOptions>& dataset_option_table();
// The count of a random map set and its sources per map (its seed is bound apart).
// dataset/map_set.cpp.
const OptionTable<MapSetOptions>& map_set_option_table();

}  // namespace plumekit::dataset
