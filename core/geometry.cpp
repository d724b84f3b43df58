#include "core/geometry.hpp"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <functional>
#include <sstream>

namespace plumekit {

std::size_t Vec2Hash::operator()(Vec2 p) const {
  // + 0.0 folds -0.0 into 0.0, which compare equal.
  const double x = p.x + 0.0, y = p.y + 0.0;
  std::uint64_t a, b;
  std::memcpy(&a, &x, sizeof a);
  std::memcpy(&b, &y, sizeof b);
  return std::hash<std::uint64_t>()(a * 0x9E3779B97F4A7C15ull ^ (b + (a << 6) + (a >> 2)));
}

namespace {

// Tolerance relative to the coordinates involved: collinearity and on-segment
// tests treat anything within ~1e-12 of the local scale as exact.
double tolerance(Vec2 a, Vec2 b, Vec2 c) {
  const double scale = std::max({std::abs(a.x), std::abs(a.y), std::abs(b.x), std::abs(b.y),
                                 std::abs(c.x), std::abs(c.y), 1.0});
  return 1e-12 * scale * scale;
}

int orientation_sign(Vec2 a, Vec2 b, Vec2 c) {
  const double o = orient(a, b, c);
  const double tol = tolerance(a, b, c);
  return o > tol ? 1 : (o < -tol ? -1 : 0);
}

bool within_box(Vec2 p, Vec2 a, Vec2 b) {
  const double tol =
      1e-12 * std::max({std::abs(a.x), std::abs(a.y), std::abs(b.x), std::abs(b.y), 1.0});
  return p.x >= std::min(a.x, b.x) - tol && p.x <= std::max(a.x, b.x) + tol &&
         p.y >= std::min(a.y, b.y) - tol && p.y <= std::max(a.y, b.y) + tol;
}

}  // namespace

double signed_area(const Polygon& poly) {
  double twice = 0.0;
  for (std::size_t i = 0, n = poly.size(); i < n; ++i)
    twice += cross(poly[i], poly[(i + 1) % n]);
  return 0.5 * twice;
}

Box bounding_box(const Polygon& poly) {
  Box box{{HUGE_VAL, HUGE_VAL}, {-HUGE_VAL, -HUGE_VAL}};
  for (Vec2 p : poly) {
    box.lo = {std::min(box.lo.x, p.x), std::min(box.lo.y, p.y)};
    box.hi = {std::max(box.hi.x, p.x), std::max(box.hi.y, p.y)};
  }
  return box;
}

double distance_to_segment(Vec2 p, Vec2 a, Vec2 b) {
  const Vec2 ab = b - a;
  const double len2 = dot(ab, ab);
  const double t = len2 > 0.0 ? std::clamp(dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
  return norm(p - (a + t * ab));
}

bool point_on_segment(Vec2 p, Vec2 a, Vec2 b) {
  return orientation_sign(a, b, p) == 0 && within_box(p, a, b);
}

bool segments_intersect(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
  const int o1 = orientation_sign(a, b, c), o2 = orientation_sign(a, b, d);
  const int o3 = orientation_sign(c, d, a), o4 = orientation_sign(c, d, b);
  if (o1 != o2 && o3 != o4 && o1 != 0 && o2 != 0 && o3 != 0 && o4 != 0) return true;
  return (o1 == 0 && within_box(c, a, b)) || (o2 == 0 && within_box(d, a, b)) ||
         (o3 == 0 && within_box(a, c, d)) || (o4 == 0 && within_box(b, c, d));
}

Location locate(const Polygon& poly, Vec2 p) {
  // Crossing number with a half-open rule on y, after an explicit boundary test.
  bool inside = false;
  for (std::size_t i = 0, n = poly.size(), j = n - 1; i < n; j = i++) {
    const Vec2 a = poly[j], b = poly[i];
    if (point_on_segment(p, a, b)) return Location::Boundary;
    if ((a.y > p.y) != (b.y > p.y)) {
      const double x_at = a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y);
      if (p.x < x_at) inside = !inside;
    }
  }
  return inside ? Location::Inside : Location::Outside;
}

std::optional<std::string> simplicity_fault(const Polygon& poly) {
  const std::size_t n = poly.size();
  if (n < 3) return "only " + std::to_string(n) + " vertices; a polygon needs at least 3";
  for (std::size_t i = 0; i < n; ++i) {
    if (poly[i] == poly[(i + 1) % n])
      return "vertex " + std::to_string(i) + " " + to_string(poly[i]) + " is repeated";
  }
  auto edge = [&](std::size_t i) {
    return "edge " + std::to_string(i) + " " + to_string(poly[i]) + "-" +
           to_string(poly[(i + 1) % n]);
  };
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 a = poly[i], b = poly[(i + 1) % n];
    for (std::size_t j = i + 1; j < n; ++j) {
      const Vec2 c = poly[j], d = poly[(j + 1) % n];
      const bool next = j == i + 1, wraps = i == 0 && j == n - 1;
      if (next || wraps) {
        // Adjacent edges share one vertex; they must not fold back onto each other.
        const Vec2 shared = next ? b : a, far_mine = next ? a : b, far_theirs = next ? d : c;
        if (orientation_sign(far_mine, shared, far_theirs) == 0 &&
            dot(far_mine - shared, far_theirs - shared) > 0.0)
          return edge(i) + " folds back onto " + edge(j);
        continue;
      }
      if (segments_intersect(a, b, c, d)) return edge(i) + " crosses or touches " + edge(j);
    }
  }
  const Box box = bounding_box(poly);
  const double extent = std::max(box.hi.x - box.lo.x, box.hi.y - box.lo.y);
  if (std::abs(signed_area(poly)) <= 1e-12 * extent * extent) return "zero area";
  return std::nullopt;
}

std::string to_string(Vec2 p) {
  std::ostringstream s;
  s.precision(10);
  s << '(' << p.x << ", " << p.y << ')';
  return s.str();
}

Vec2 point_along(const std::vector<Vec2>& path, double d) {
  for (std::size_t k = 1; k < path.size(); ++k) {
    const double leg = norm(path[k] - path[k - 1]);
    if (d <= leg && leg > 0.0) return path[k - 1] + (d / leg) * (path[k] - path[k - 1]);
    d -= leg;
  }
  return path.back();
}

std::vector<Vec2> path_prefix(const std::vector<Vec2>& path, double d) {
  std::vector<Vec2> prefix;
  if (path.empty()) return prefix;
  prefix.push_back(path.front());
  for (std::size_t k = 1; k < path.size(); ++k) {
    const double leg = norm(path[k] - path[k - 1]);
    if (d < leg) {
      if (d > 0.0) prefix.push_back(path[k - 1] + (d / leg) * (path[k] - path[k - 1]));
      return prefix;
    }
    prefix.push_back(path[k]);
    d -= leg;
  }
  return prefix;
}

}  // namespace plumekit
