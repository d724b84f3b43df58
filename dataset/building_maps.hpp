#pragma once
// The "building" random-map family: floor plans of single-storey buildings,
// 6 to 30 m a side by default. The arena is the building's footprint; its outer
// walls are 0.2 m obstacle bands along the arena's edge. Inside: a corridor
// with rooms on both sides (long buildings, usually) or rooms alone, split
// recursively; every interior wall (0.1 m) has a door; furniture stands in the
// rooms. Inlets and outlets are doors (a gap in the outer wall, the opening on
// the arena wall) or windows (the opening on the outer wall's inner edge, an
// obstacle's edge). Written as plumekit-map/2. Every coordinate is a multiple
// of 0.1 m, so flow grids of 0.1 m or 0.05 m cells follow the walls exactly.
#include <random>
#include <string>

#include "dataset/random_maps.hpp"
#include "map/map.hpp"

namespace plumekit::dataset {

// Draws building maps from `rng` until one keeps building_fault()'s promises
// (at most options.max_attempts draws), named `name`. Deterministic in rng.
// InputError when none does.
RandomMap random_building(const RandomMapOptions& options, std::mt19937_64& rng,
                          const std::string& name);

// The promises, each checked on a grid of `cell` metres (5 cm in the
// generator). "" when all hold, else which one fails:
// - the map validates (validate_map);
// - its size per side is within [building_min_size, building_max_size];
// - every opening is open (openings_open);
// - the free space is one region (free_space_connected);
// - air can cross (inlet_reaches_outlet on the label grid);
// - a robot passes every door and corridor (robot_region_connected at radius
//   building_passage / 2 - cell: the grid's round-off).
std::string building_fault(const Map& map, const RandomMapOptions& options, double cell = 0.05);

// The free point half a cell beside every stretch of `cell` along every
// opening, on its free side, is free space.
bool openings_open(const Map& map, double cell);

// The free cells of the label grid (`cell` metres) form one 4-connected region.
bool free_space_connected(const Map& map, double cell);

// The cells (`cell` metres) whose centre lies at least `radius` from every
// obstacle and every solid stretch of the arena's walls (openings on walls are
// not solid) form one 4-connected, non-empty region: a disk of that radius
// reaches every part of the free space a passage at least 2 * radius wide
// leads to.
bool robot_region_connected(const Map& map, double radius, double cell);

}  // namespace plumekit::dataset
