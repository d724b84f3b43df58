#pragma once
// The map model: a rectangular arena with an inlet, an outlet, polygonal
// obstacles and optional ground-truth sources. Files: plumekit-map/1 (map_json.hpp).
#include <string>
#include <vector>

#include "core/geometry.hpp"

namespace plumekit {

enum class Side { Left, Right, Bottom, Top };
enum class Profile { Uniform, Parabolic };

const char* to_string(Side side);
const char* to_string(Profile profile);

// A span of one arena wall. Position along the wall is measured from the
// arena's lower-left corner: along y for the left/right walls, along x for
// the bottom/top walls.
struct Opening {
  Side side = Side::Left;
  double from = 0.0;
  double to = 0.0;
};

struct Inlet : Opening {
  double speed = 1.0;  // m/s; the peak speed for a parabolic profile
  Profile profile = Profile::Uniform;
};

struct Map {
  std::string name;
  // The plumekit command that wrote the file ("plumekit map import-ros"), empty
  // for a map a person wrote: only a generated map file may be overwritten.
  std::string generated_by;
  double width = 0.0;   // m, along x
  double height = 0.0;  // m, along y
  Inlet inlet;
  Opening outlet;
  std::vector<Polygon> obstacles;
  std::vector<Vec2> sources;

  // Length of a wall: height for left/right, width for bottom/top.
  double wall_length(Side side) const;
  // The point `s` metres along a wall (see Opening).
  Vec2 wall_point(Side side, double s) const;
  bool in_arena(Vec2 p) const { return p.x >= 0.0 && p.x <= width && p.y >= 0.0 && p.y <= height; }
  // Index of the first obstacle whose interior or boundary holds `p`, or -1.
  int obstacle_at(Vec2 p) const;
  bool is_free(Vec2 p) const { return in_arena(p) && obstacle_at(p) < 0; }
};

// The default thesis arena: 10 x 4 m, inlet on the whole left wall at 1 m/s,
// outlet on the whole right wall, no obstacles.
Map default_arena(double width = 10.0, double height = 4.0);

}  // namespace plumekit
