#pragma once
// The map model: a rectangular arena, any number of openings (inlets and
// outlets) on the free space's boundary, polygonal obstacles, optional
// ground-truth sources and the frame that ties the arena to the user's map
// frame. Files: plumekit-map/2 and /1 (map_json.hpp).
//
// Every coordinate in a Map is in the arena frame: the arena's lower-left
// corner is (0, 0). `origin` is where that corner lies in the user's map frame
// (a ROS map's `origin`); files and every coordinate a user types or reads are
// in the map frame, and to_frame/from_frame convert.
#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include "core/geometry.hpp"

namespace plumekit {

enum class Side { Left, Right, Bottom, Top };
enum class Profile { Uniform, Parabolic };
enum class OpeningKind { Inlet, Outlet };

// The fastest inlet a map may have, m/s. plumekit's flow is incompressible,
// which holds only well below Mach 0.3: about 100 m/s in air (sound: 343 m/s).
inline constexpr double kMaxInletSpeed = 100.0;
// Why, for messages that refuse a faster inlet.
inline constexpr const char* kInletSpeedBound =
    "at most 100 m/s: plumekit's flow is incompressible, which holds only well below Mach 0.3 "
    "(about 100 m/s in air)";

const char* to_string(Side side);
const char* to_string(Profile profile);
const char* to_string(OpeningKind kind);

// A straight, axis-parallel stretch of the free space's boundary through which
// air enters (an inlet, blowing in at `speed` normal to the stretch) or leaves
// (an outlet, pressure 0). It lies on an arena wall or on an obstacle's edge,
// such as a door in a building's outer wall.
struct Opening {
  OpeningKind kind = OpeningKind::Inlet;
  Vec2 from;
  Vec2 to;
  double speed = 1.0;  // inlets: m/s, the peak speed for a parabolic profile
  Profile profile = Profile::Uniform;

  bool is_inlet() const { return kind == OpeningKind::Inlet; }
  // Runs along y (x constant); otherwise along x (y constant).
  bool vertical() const { return from.x == to.x; }
  // The constant coordinate: x for a vertical opening, y for a horizontal one.
  double line() const { return vertical() ? from.x : from.y; }
  // The span along the opening: [lo, hi] in y (vertical) or x (horizontal).
  double lo() const;
  double hi() const;
  double length() const { return hi() - lo(); }
  // The inflow speed at position s along the span (the profile's shape).
  double speed_at(double s) const;
};

// The arena frame's offset in the user's map frame (yaw is not supported:
// plumekit arenas are axis-aligned).
struct MapFrame {
  Vec2 origin;  // map-frame position of the arena's lower-left corner

  bool is_identity() const { return origin.x == 0.0 && origin.y == 0.0; }
  // Arena <-> map frame; the identity, bit for bit, when the origin is (0, 0).
  Vec2 to_frame(Vec2 arena) const { return is_identity() ? arena : arena + origin; }
  Vec2 from_frame(Vec2 framed) const { return is_identity() ? framed : framed - origin; }
};

struct Map {
  std::string name;
  // The plumekit command that wrote the file ("plumekit map import-ros"), empty
  // for a map a person wrote: only a generated map file may be overwritten.
  std::string generated_by;
  // The format version the map was read as (or is meant to be written as):
  // a tool that reads a /1 file writes /1 back, unchanged.
  int format_version = 2;
  MapFrame frame;
  double width = 0.0;   // m, along x
  double height = 0.0;  // m, along y
  std::vector<Opening> openings;
  std::vector<Polygon> obstacles;
  std::vector<Vec2> sources;
  // Robot starts for evaluation (plumekit-map/2 only): `evaluate` starts its
  // runs from these, in turn, instead of seeded random free points.
  std::vector<Vec2> starts;

  // Length of a wall: height for left/right, width for bottom/top.
  double wall_length(Side side) const;
  // The point `s` metres along a wall (y for left/right, x for bottom/top).
  Vec2 wall_point(Side side, double s) const;
  bool in_arena(Vec2 p) const { return p.x >= 0.0 && p.x <= width && p.y >= 0.0 && p.y <= height; }
  // Index of the first obstacle whose interior or boundary holds `p`, or -1.
  int obstacle_at(Vec2 p) const;
  bool is_free(Vec2 p) const { return in_arena(p) && obstacle_at(p) < 0; }

  // Lengths below this are round-off (coordinates equal within it).
  double round_off() const { return 1e-9 * std::max({width, height, 1.0}); }
  // How far off a boundary a point is probed to see which side is free.
  double probe_distance() const { return 1e-6 * std::max({width, height, 1.0}); }
  // Arena <-> map frame (MapFrame).
  bool has_frame() const { return !frame.is_identity(); }
  Vec2 to_frame(Vec2 arena) const { return frame.to_frame(arena); }
  Vec2 from_frame(Vec2 framed) const { return frame.from_frame(framed); }

  // The arena wall an opening lies on, if any.
  std::optional<Side> wall_of(const Opening& o) const;
  // The unit normal of an opening that points into the free space: into the
  // arena for a wall, away from the obstacle for an obstacle's edge.
  Vec2 inward_normal(const Opening& o) const;
  // The first inlet / outlet (every valid map has one of each).
  const Opening& first_inlet() const;
  const Opening& first_outlet() const;
  // The fastest inlet's speed: the flow's reference speed.
  double reference_speed() const;
  // Index of the opening on an arena wall that covers position s along it,
  // or -1 (a plain wall).
  int opening_on_wall(Side side, double s) const;
  // Index of the opening on the grid line `line` (x = line for a vertical
  // line) whose span covers s, where an opening counts as on the line when it
  // lies within half a cell (`half_cell`) of it: the grid face a rasterized
  // obstacle edge lands on. -1 when none.
  int opening_on_line(bool vertical, double line, double half_cell, double s) const;
};

// Why the arena point `p` cannot hold a source or a robot, in the map's frame ("(4.5, 0.5) is
// outside the arena (100...106 x -50...-47)", "... is inside obstacles[0] of map room"); "" if
// it can. The one wording of every such refusal (CLI, Python, predict).
std::string point_fault(const Map& map, Vec2 p);

// The number of obstacle vertices, for summaries.
std::size_t vertex_count(const Map& map);

// An opening along part of an arena wall, [from, to] metres along it.
Opening wall_opening(const Map& map, Side side, double from, double to, OpeningKind kind,
                     double speed = 1.0, Profile profile = Profile::Uniform);

// The default thesis arena: 10 x 4 m, inlet on the whole left wall at 1 m/s,
// outlet on the whole right wall, no obstacles.
Map default_arena(double width = 10.0, double height = 4.0);

}  // namespace plumekit
