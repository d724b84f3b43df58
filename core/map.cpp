#include "core/map.hpp"

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

Map default_arena(double width, double height) {
  Map map;
  map.name = "arena";
  map.width = width;
  map.height = height;
  map.inlet.side = Side::Left;
  map.inlet.from = 0.0;
  map.inlet.to = height;
  map.outlet.side = Side::Right;
  map.outlet.from = 0.0;
  map.outlet.to = height;
  return map;
}

}  // namespace plumekit
