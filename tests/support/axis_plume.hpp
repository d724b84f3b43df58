#pragma once
// The world tests' plume: along y = 2 from (2, 2) in a uniform 1 m/s wind over an empty 10 x 4 m
// arena, with a light release and a short spin-up, so that a test's world is quick to build.
#include <string>

#include "map/map.hpp"
#include "support/uniform_wind.hpp"
#include "world/simulated_world.hpp"

namespace plumekit::test {

struct AxisPlume {
  Map map = default_arena(10.0, 4.0);
  cfd::WindField wind = uniform_wind(10.0, 4.0, 0.05, 1.0);
  Vec2 source{2.0, 2.0};
  // The world's options with the quick plume and the named gas sensor; the rest default.
  static world::WorldOptions quick_options(const std::string& sensor = "ideal") {
    world::WorldOptions o;
    o.filament.release_per_second = 100.0;
    o.filament.min_spinup = 2.0;
    o.filament.max_spinup = 6.0;
    o.sensor = world::gas_sensor_preset(sensor);
    return o;
  }
};

}  // namespace plumekit::test
