#pragma once
// Why air cannot cross a map: the free regions of a label grid
// (map/rasterize.hpp), which openings each one touches, and advice naming
// the sealed ones. `map validate` and `map import-ros` say the same thing.
#include <string>
#include <vector>

#include "core/grid.hpp"
#include "map/map.hpp"

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

// Which of `points` (arena frame) lie in a pocket of free space sealed off
// from every opening on the grid of `labels`: no path of free cells joins the
// cell holding the point (or, when that cell is solid, the free cells around
// it) to a cell beside an opening. A point with no free cell around it is not
// in a pocket (it is inside an obstacle, as far as the grid can tell).
std::vector<bool> in_sealed_pocket(const Grid<std::uint8_t>& labels,
                                   const std::vector<Vec2>& points);
// What `map validate` and `localize` say of a point in such a pocket.
inline constexpr const char* kSealedPocket =
    "lies in a pocket of free space sealed off from every opening: no air reaches it, so gas "
    "released there never leaves it";

// An opening that no cell of a grid opens onto: no cell face's middle lies on
// its span (Map::opening_on_line), as happens when it is shorter than a cell.
// A grid that misses one is too coarse for the map, whatever the map's passages.
struct MissedOpening {
  std::size_t index = 0;  // into map.openings
  double length = 0.0;    // m
  double cell = 0.0;      // m, the cell side along it
};
// Shortest first.
std::vector<MissedOpening> openings_missed_by_grid(const Map& map, const GridShape& shape);
// "the inlet" (a /1 map) or "openings[2] (an outlet)".
std::string opening_name(const Map& map, std::size_t k);

// Empty when air can cross the map; else why not and how to fix it: which
// openings touch no free space, the free region the inlets open into (its
// size and a point in it, map frame), the largest free region that touches
// no opening. `unknown_hint` adds the unknown-space advice of a ROS import
// (field "ros.unknown"); the opening advice names "ros.inlets"/"ros.outlets"
// when `opening_fields` is set, else the map file's openings.
std::vector<std::string> sealed_map_advice(const Map& map, const FreeSpace& space,
                                           bool unknown_hint, bool opening_fields);

}  // namespace plumekit
