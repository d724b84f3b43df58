#include "methods/wind_statistics.hpp"

#include <algorithm>
#include <cmath>

namespace plumekit::methods {

Vec2 heading(double a) {
  return {std::cos(a), std::sin(a)};
}

double angle_of(Vec2 v) {
  return (v.x == 0.0 && v.y == 0.0) ? 0.0 : std::atan2(v.y, v.x);
}

Vec2 rotate(Vec2 v, double a) {
  const double c = std::cos(a), s = std::sin(a);
  return {c * v.x - s * v.y, s * v.x + c * v.y};
}

double wrap_angle(double a) {
  a = std::remainder(a, 2.0 * kPi);  // [-pi, pi]
  return a <= -kPi ? a + 2.0 * kPi : a;
}

double degrees(double radians) {
  return radians * 180.0 / kPi;
}

double radians(double degrees) {
  return degrees * kPi / 180.0;
}

CircularStatistics circular_statistics(const std::vector<double>& angles) {
  CircularStatistics s;
  if (angles.empty()) return s;
  double c = 0.0, si = 0.0;
  for (double a : angles) {
    c += std::cos(a);
    si += std::sin(a);
  }
  c /= static_cast<double>(angles.size());
  si /= static_cast<double>(angles.size());
  s.mean = angle_of({c, si});
  s.variance = std::clamp(1.0 - std::hypot(c, si), 0.0, 1.0);
  return s;
}

Vec2 upwind(Vec2 wind) {
  const double n = norm(wind);
  return n < 1e-9 ? Vec2{} : (-1.0 / n) * wind;
}

}  // namespace plumekit::methods
