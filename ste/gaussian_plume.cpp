#include "ste/gaussian_plume.hpp"

#include <cmath>

#include "core/geometry.hpp"

namespace plumekit::ste {

GaussianPlume::GaussianPlume(const Map& map, const GaussianPlumeBounds& b)
    : parameters_{{"x", 0.0, map.width},
                  {"y", 0.0, map.height},
                  {"Q", 0.0, b.q_max},
                  {"a", b.a_min, b.a_max},
                  {"b", b.b_min, b.b_max}},
      // The wind blows in through the first inlet; a parabolic profile's mean is
      // 2/3 of its peak.
      downwind_(map.inward_normal(map.first_inlet())),
      speed_(map.first_inlet().profile == Profile::Parabolic ? map.first_inlet().speed * 2.0 / 3.0
                                                             : map.first_inlet().speed) {}

double GaussianPlume::predict_at(const double* m, Vec2 p) const {
  const Vec2 r{p.x - m[0], p.y - m[1]};
  const double d = dot(r, downwind_);
  if (d <= 0.0) return 0.0;
  const double c = cross(downwind_, r);
  const double sigma = m[3] * d + m[4];
  return m[2] / (2.0 * kPi * speed_ * sigma) * std::exp(-c * c / (2.0 * sigma * sigma));
}

std::vector<double> GaussianPlume::predict(const std::vector<double>& params,
                                           const std::vector<Vec2>& points) const {
  std::vector<double> out(points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
    out[i] = predict_at(params.data(), points[i]);
  return out;
}

}  // namespace plumekit::ste
