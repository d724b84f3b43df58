#pragma once
// Random cluttered maps in the source thesis's families (Rahbar 2021,
// Fig. 14.1): one rectangle, two separate rectangles, an L-shape, a U-shape,
// axis-aligned, at random sizes, positions and orientations; on request also
// two more cluttered families beyond the thesis's: three rectangles, and an L
// or U with a rectangle; and building floor plans (building_maps.hpp), whose
// arena is the building, not the 10 x 4 m one. Every map keeps
// its inlet and outlet open, lets air and a robot through (see the checks in
// random_map()), and is a pure function of (seed, index).
#include <cstdint>
#include <string>
#include <vector>

#include "core/grid.hpp"
#include "map/map.hpp"

namespace plumekit::dataset {

struct RandomMapOptions {
  double width = 10.0;       // m, the thesis arena
  double height = 4.0;       // m
  double inlet_speed = 1.0;  // m/s, uniform over the whole left wall; outlet the whole right wall
  // Obstacles stay this far from the inlet and outlet walls, so both stay open
  // and the flow is developed before it meets an obstacle.
  double end_clearance = 1.0;
  // A robot of this radius (plus safety) must be able to go from the inlet to
  // the outlet, and every gap between two obstacles, or an obstacle and a wall,
  // is either closed (touching) or at least min_gap wide.
  double robot_margin = 0.15;
  double min_gap = 0.4;
  int max_attempts = 10000;
  // The "building" family (building_maps.hpp): each side of the floor is drawn
  // uniformly from [building_min_size, building_max_size], and every door,
  // corridor and gap beside furniture is at least building_passage wide: a
  // robot of the planner's 0.15 m margin with room to spare, and a door.
  double building_min_size = 6.0;   // m
  double building_max_size = 30.0;  // m
  double building_passage = 0.8;    // m
  // The families drawn from, each equally likely. The default is the thesis's four; with
  // them, map i is the same as before the extra families existed.
  std::vector<std::string> families = thesis_families();
  static std::vector<std::string> thesis_families() {
    return {"rectangle", "two-rectangles", "l-shape", "u-shape"};
  }
  // Every family random_map() knows: the thesis's and three-rectangles, shape-and-rectangle,
  // building.
  static std::vector<std::string> known_families();

  // Throws OptionError naming the field ("maps.width", "maps.families", ...):
  // an unknown family names it and lists the known ones. random_map() calls it.
  void validate() const;
  // The building_* fields ("maps.building_min_size", ...).
  void validate_building() const;
};

struct RandomMap {
  Map map;
  std::string family;  // one of RandomMapOptions::known_families()
  int attempts = 0;    // draws rejected by the checks, plus one
};

// Map number `index` of the maps drawn from `seed`. Deterministic. `redraw`
// > 0 gives replacement draws for the same index (the dataset generator uses
// them when the steady flow of a map does not converge); their names end in
// -rN-FAMILY.
RandomMap random_map(const RandomMapOptions& options, std::uint64_t seed, std::uint64_t index,
                     std::uint64_t redraw = 0);

// The family a random map's name ends with, or "" when it is none of them.
std::string family_of(const std::string& map_name);

// The cells of a map's flow grid and which of them are solid: an obstacle's cells, a narrow gap's
// and those of a pocket of free space that no path of air joins to an outlet (sealed, as the flow
// solver seals them: cfd/staggered_grid.hpp).
struct FlowCells {
  GridShape shape;
  std::vector<std::uint8_t> solid;
  // Whether the cell that holds `p` is air the flow reaches.
  bool fluid_at(Vec2 p) const;
};
// The cells of `map`'s flow grid with plumekit's default flow options, without solving the flow.
FlowCells default_flow_cells(const Map& map);

// `count` sources uniformly over the free space at least `clearance` metres
// from every obstacle and wall, in fluid cells of the flow grid `flow` (nullptr: the map's default
// grid, default_flow_cells), drawn from (seed, map index). Deterministic: a draw that is not in
// such a cell is rejected and the next one taken, so every plume model can release at a source
// (a point in a sealed pocket has no flow, and the advection-diffusion model no cell to release
// in).
std::vector<Vec2> random_sources(const Map& map, int count, double clearance, std::uint64_t seed,
                                 std::uint64_t map_index, const FlowCells* flow = nullptr);

// Robot check: cells (0.05 m) whose centre is at least `margin` from every
// solid surface connect the inlet side to the outlet side.
bool robot_can_cross(const Map& map, double margin);

// Uniform double in [0, 1) from 53 random bits: the same on every platform
// (std::uniform_real_distribution is not).
double unit_uniform(std::uint64_t bits);

}  // namespace plumekit::dataset
