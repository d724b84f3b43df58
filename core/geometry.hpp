#pragma once
// Plain 2-D geometry on doubles: points, polygons, predicates.
// Exact predicates for planning live in planner/ (CGAL); these serve validation,
// rasterization and drawing, where a tolerance of ~1e-12 m is harmless.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace plumekit {

struct Vec2 {
  double x = 0.0;
  double y = 0.0;
};

inline Vec2 operator+(Vec2 a, Vec2 b) {
  return {a.x + b.x, a.y + b.y};
}
inline Vec2 operator-(Vec2 a, Vec2 b) {
  return {a.x - b.x, a.y - b.y};
}
inline Vec2 operator*(double s, Vec2 a) {
  return {s * a.x, s * a.y};
}
inline bool operator==(Vec2 a, Vec2 b) {
  return a.x == b.x && a.y == b.y;
}
inline bool operator!=(Vec2 a, Vec2 b) {
  return !(a == b);
}
// One pi for every stage (C++17 has no std::numbers).
inline constexpr double kPi = 3.14159265358979323846;

// Hash of a point's exact coordinates, consistent with operator== (-0.0 and 0.0 hash alike):
// for maps keyed by points that are copied, never recomputed.
struct Vec2Hash {
  std::size_t operator()(Vec2 p) const;
};
inline double dot(Vec2 a, Vec2 b) {
  return a.x * b.x + a.y * b.y;
}
inline double cross(Vec2 a, Vec2 b) {
  return a.x * b.y - a.y * b.x;
}
inline double norm(Vec2 a) {
  return std::hypot(a.x, a.y);
}
inline bool is_finite(Vec2 a) {
  return std::isfinite(a.x) && std::isfinite(a.y);
}

// A point or vector in 3-D (the wind tunnel of seed 004 chs. 11 and 17: x downwind, y across,
// z up), metres.
struct Vec3 {
  double x = 0.0;
  double y = 0.0;
  double z = 0.0;
};
inline Vec3 operator+(Vec3 a, Vec3 b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
inline Vec3 operator-(Vec3 a, Vec3 b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
inline Vec3 operator*(double s, Vec3 a) {
  return {s * a.x, s * a.y, s * a.z};
}
inline double norm(Vec3 a) {
  return std::sqrt(a.x * a.x + a.y * a.y + a.z * a.z);
}
inline bool is_finite(Vec3 a) {
  return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z);
}

// An axis-aligned box in 3-D: the wind tunnel's volume.
struct Box3 {
  Vec3 lo;
  Vec3 hi;
  bool contains(Vec3 p) const {
    return p.x >= lo.x && p.x <= hi.x && p.y >= lo.y && p.y <= hi.y && p.z >= lo.z && p.z <= hi.z;
  }
  // The box shrunk by m on every side (a margin kept from the walls).
  Box3 inset(double m) const { return {lo + Vec3{m, m, m}, hi - Vec3{m, m, m}}; }
  // The point of the box nearest to p.
  Vec3 clamp(Vec3 p) const {
    return {std::clamp(p.x, lo.x, hi.x), std::clamp(p.y, lo.y, hi.y), std::clamp(p.z, lo.z, hi.z)};
  }
};

// Vertices in order, either orientation, last edge closes back to the first.
using Polygon = std::vector<Vec2>;

struct Box {
  Vec2 lo;
  Vec2 hi;
  bool contains(Vec2 p) const { return p.x >= lo.x && p.x <= hi.x && p.y >= lo.y && p.y <= hi.y; }
};

// > 0 when a, b, c turn counter-clockwise, < 0 clockwise, 0 collinear.
inline double orient(Vec2 a, Vec2 b, Vec2 c) {
  return cross(b - a, c - a);
}

double signed_area(const Polygon& poly);  // > 0 for counter-clockwise
Box bounding_box(const Polygon& poly);
double distance_to_segment(Vec2 p, Vec2 a, Vec2 b);
bool point_on_segment(Vec2 p, Vec2 a, Vec2 b);
// Closed segments [a,b] and [c,d] share at least one point.
bool segments_intersect(Vec2 a, Vec2 b, Vec2 c, Vec2 d);

enum class Location { Outside, Boundary, Inside };
Location locate(const Polygon& poly, Vec2 p);
// Inside or on the boundary.
inline bool covers(const Polygon& poly, Vec2 p) {
  return locate(poly, p) != Location::Outside;
}

// Why `poly` is not a simple polygon (too few vertices, a repeated vertex, zero
// area, two edges that cross or touch), or nullopt when it is simple.
std::optional<std::string> simplicity_fault(const Polygon& poly);

// "(1.5, 2)" — for messages.
std::string to_string(Vec2 p);

// The point `d` metres along a polyline (its end beyond its length, its start before 0).
Vec2 point_along(const std::vector<Vec2>& path, double d);
// The polyline's first `d` metres: its vertices before d and the point at d.
std::vector<Vec2> path_prefix(const std::vector<Vec2>& path, double d);

}  // namespace plumekit
