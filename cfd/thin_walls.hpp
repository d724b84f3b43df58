#pragma once
// Thin walls: obstacles that the flow grid lets air through. A cell is solid
// when its centre lies in an obstacle (map/rasterize.hpp), so a wall thinner
// than a cell may hold no centre where it crosses a row or column of cells:
// the two free cells on either side of it then share a face and the flow runs
// through the wall, while the planner and the plume models still see it. It is
// the counterpart of a narrow gap (gap_closing.hpp), which the grid closes; a
// thin wall is reported, with the cell that resolves it.
//
// A leak is a pair of 4-neighbouring free cells whose centres' segment enters
// an obstacle's interior. The search walks each obstacle edge across the rows
// and columns of cell centres, so it takes time in proportion to the edges'
// lengths in cells, and tests only the pairs of free cells it meets.
#include <cstdint>
#include <string>
#include <vector>

#include "core/grid.hpp"
#include "map/map.hpp"

namespace plumekit::cfd {

struct ThinWall {
  int obstacle = -1;       // index into map.obstacles
  int leaks = 0;           // pairs of free cells whose shared face crosses it
  double thickness = 0.0;  // m, its extent along the thinnest leaking pair's axis
  Vec2 at;                 // arena frame: the middle of that pair's centres
};

// The obstacles the grid `solid` (row-major, 1 solid: the occupancy with its
// narrow gaps closed, as the solver uses it) lets air through, in obstacle order.
std::vector<ThinWall> find_thin_walls(const Map& map, const GridShape& shape,
                                      const std::vector<std::uint8_t>& solid);

// What a flow reports of them, for people: positions in the map frame.
struct ThinWalls {
  std::vector<ThinWall> walls;  // `at` in the map frame
  double resolving_cell = 0.0;  // m, a cell that puts a solid cell in the thinnest (0: none)
};
ThinWalls summarize_thin_walls(const Map& map, const std::vector<ThinWall>& walls);

// "the 0.1 m cells do not resolve 1 obstacle, so air flows through it where the
// planner sees a wall: obstacles[2] at (5.08, 1.5), 0.04 m thick (12 cell faces
// through it); a cell of 0.04 m or finer resolves it". Empty when none.
std::string thin_walls_text(const ThinWalls& thin, double cell);

}  // namespace plumekit::cfd
