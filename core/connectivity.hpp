#pragma once
// Why air cannot cross a map: the free regions of a label grid
// (core/rasterize.hpp), which openings each one touches, and advice naming
// the sealed ones. `map validate` and `map import-ros` say the same thing.
#include <string>
#include <vector>

#include "core/grid.hpp"
#include "core/map.hpp"

namespace plumekit {

// One 4-connected region of non-obstacle cells.
struct FreeRegion {
  int cells = 0;
  double area_m2 = 0.0;
  Vec2 point;  // arena frame: the member cell nearest the region's centroid
  bool inlet = false;
  bool outlet = false;
};

struct FreeSpace {
  std::vector<FreeRegion> regions;  // largest first
  int inlet_cells = 0;              // free cells some inlet opens into
  int outlet_cells = 0;             // free cells some outlet opens into
  double free_area_m2 = 0.0;
  // Some region touches both an inlet and an outlet.
  bool inlet_reaches_outlet() const;
};

FreeSpace free_regions(const Grid<std::uint8_t>& labels);

// Empty when air can cross the map; else why not and how to fix it: which
// openings touch no free space, the free region the inlets open into (its
// size and a point in it, map frame), the largest free region that touches
// no opening. `unknown_hint` adds the unknown-space advice of a ROS import
// (field "ros.unknown"); the opening advice names "ros.inlets"/"ros.outlets"
// when `opening_fields` is set, else the map file's openings.
std::vector<std::string> sealed_map_advice(const Map& map, const FreeSpace& space,
                                           bool unknown_hint, bool opening_fields);

}  // namespace plumekit
