#include "map/map.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/option_check.hpp"

namespace plumekit {

const char* to_string(Side side) {
  switch (side) {
    case Side::Left:
      return "left";
    case Side::Right:
      return "right";
    case Side::Bottom:
      return "bottom";
    case Side::Top:
      return "top";
  }
  return "?";
}

const char* to_string(Profile profile) {
  return profile == Profile::Uniform ? "uniform" : "parabolic";
}

const char* to_string(OpeningKind kind) {
  return kind == OpeningKind::Inlet ? "inlet" : "outlet";
}

double Opening::lo() const {
  return vertical() ? std::min(from.y, to.y) : std::min(from.x, to.x);
}

double Opening::hi() const {
  return vertical() ? std::max(from.y, to.y) : std::max(from.x, to.x);
}

double Opening::speed_at(double s) const {
  if (profile == Profile::Uniform) return speed;
  const double t = (s - lo()) / (hi() - lo());
  return speed * 4.0 * t * (1.0 - t);
}

double Map::wall_length(Side side) const {
  return side == Side::Left || side == Side::Right ? height : width;
}

Vec2 Map::wall_point(Side side, double s) const {
  switch (side) {
    case Side::Left:
      return {0.0, s};
    case Side::Right:
      return {width, s};
    case Side::Bottom:
      return {s, 0.0};
    case Side::Top:
      return {s, height};
  }
  return {};
}

int Map::obstacle_at(Vec2 p) const {
  for (std::size_t i = 0; i < obstacles.size(); ++i) {
    if (covers(obstacles[i], p)) return static_cast<int>(i);
  }
  return -1;
}

std::string point_fault(const Map& map, Vec2 p) {
  const Vec2 lo = map.to_frame({0.0, 0.0}), hi = map.to_frame({map.width, map.height});
  if (!is_finite(p) || !map.in_arena(p))
    return to_string(map.to_frame(p)) + " is outside the arena (" + compact(lo.x) + "..." +
           compact(hi.x) + " x " + compact(lo.y) + "..." + compact(hi.y) + ")";
  const int o = map.obstacle_at(p);
  if (o >= 0)
    return to_string(map.to_frame(p)) + " is inside obstacles[" + std::to_string(o) + "] of map " +
           map.name;
  return "";
}

std::optional<Side> Map::wall_of(const Opening& o) const {
  if (o.vertical()) {
    if (o.line() == 0.0) return Side::Left;
    if (o.line() == width) return Side::Right;
  } else {
    if (o.line() == 0.0) return Side::Bottom;
    if (o.line() == height) return Side::Top;
  }
  return std::nullopt;
}

Vec2 Map::inward_normal(const Opening& o) const {
  const Vec2 n = o.vertical() ? Vec2{1.0, 0.0} : Vec2{0.0, 1.0};
  if (const auto wall = wall_of(o))
    return *wall == Side::Left || *wall == Side::Bottom ? n : -1.0 * n;
  // The free side of an obstacle's edge: probe a little off its middle.
  const double mid = 0.5 * (o.lo() + o.hi());
  const Vec2 at = o.vertical() ? Vec2{o.line(), mid} : Vec2{mid, o.line()};
  return is_free(at + probe_distance() * n) ? n : -1.0 * n;
}

const Opening& Map::first_inlet() const {
  for (const Opening& o : openings)
    if (o.is_inlet()) return o;
  throw std::logic_error("map '" + name + "' has no inlet");
}

const Opening& Map::first_outlet() const {
  for (const Opening& o : openings)
    if (!o.is_inlet()) return o;
  throw std::logic_error("map '" + name + "' has no outlet");
}

double Map::reference_speed() const {
  double u = 0.0;
  for (const Opening& o : openings)
    if (o.is_inlet()) u = std::max(u, o.speed);
  return u;
}

int Map::opening_on_wall(Side side, double s) const {
  for (std::size_t k = 0; k < openings.size(); ++k) {
    const Opening& o = openings[k];
    if (wall_of(o) == side && s >= o.lo() && s <= o.hi()) return static_cast<int>(k);
  }
  return -1;
}

int Map::opening_on_line(bool vertical, double line, double half_cell, double s) const {
  // An opening exactly half a cell off (an odd pixel edge at an even cell)
  // must not miss by round-off.
  const double reach = half_cell * (1.0 + 1e-9);
  for (std::size_t k = 0; k < openings.size(); ++k) {
    const Opening& o = openings[k];
    if (o.vertical() == vertical && std::abs(o.line() - line) <= reach && s >= o.lo() &&
        s <= o.hi())
      return static_cast<int>(k);
  }
  return -1;
}

std::size_t vertex_count(const Map& map) {
  std::size_t n = 0;
  for (const Polygon& p : map.obstacles)
    n += p.size();
  return n;
}

Opening wall_opening(const Map& map, Side side, double from, double to, OpeningKind kind,
                     double speed, Profile profile) {
  Opening o;
  o.kind = kind;
  o.from = map.wall_point(side, from);
  o.to = map.wall_point(side, to);
  o.speed = speed;
  o.profile = profile;
  return o;
}

Map default_arena(double width, double height) {
  Map map;
  map.name = "arena";
  map.width = width;
  map.height = height;
  map.openings.push_back(wall_opening(map, Side::Left, 0.0, height, OpeningKind::Inlet));
  map.openings.push_back(wall_opening(map, Side::Right, 0.0, height, OpeningKind::Outlet));
  return map;
}

}  // namespace plumekit
