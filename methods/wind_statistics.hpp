#pragma once
// Directions and their statistics (seed 000 App. A), shared by the methods that steer by the wind.
// Angles are mathematical (radians, counter-clockwise from +x) throughout; a wind vector points
// downwind, so the upwind heading is its angle plus pi.
#include <vector>

#include "core/geometry.hpp"

namespace plumekit::methods {

// The unit vector at angle `a` (radians).
Vec2 heading(double a);
// The angle of `v` in (-pi, pi]; 0 for the zero vector.
double angle_of(Vec2 v);
// `v` turned counter-clockwise by `a` radians.
Vec2 rotate(Vec2 v, double a);
// `a` wrapped to (-pi, pi].
double wrap_angle(double a);
double degrees(double radians);
double radians(double degrees);

// The mean direction (atan2 of the mean sine and cosine) and the circular variance
// S0 = 1 - R, R the mean resultant length (S0 in [0, 1]; 1 for no direction at all).
struct CircularStatistics {
  double mean = 0.0;
  double variance = 1.0;
};
CircularStatistics circular_statistics(const std::vector<double>& angles);

// The upwind unit vector of a wind, or nullopt-like (0, 0) for a calm (|wind| below 1e-9 m/s).
Vec2 upwind(Vec2 wind);

}  // namespace plumekit::methods
