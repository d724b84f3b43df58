#pragma once
// Helpers shared by the planner tests: small maps, a seeded random map
// generator (rectangles, L- and U-shapes in a 10 x 4 m arena, as in the thesis),
// and an independent clearance measure on plain doubles.
#include <algorithm>
#include <random>
#include <vector>

#include "core/error.hpp"
#include "core/geometry.hpp"
#include "map/map.hpp"
#include "map/map_json.hpp"

namespace plumekit::planner::testing {

inline Polygon rect(double x0, double y0, double x1, double y1) {
  return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
}

inline Map map_with(std::vector<Polygon> obstacles, double w = 10.0, double h = 4.0) {
  Map m = default_arena(w, h);
  m.obstacles = std::move(obstacles);
  return m;
}

// 8 x 4 m, a wall at x = 4 from the floor to y = 3: a 1 m door at the top.
inline Map two_rooms() {
  Map m = map_with({rect(3.9, 0.0, 4.1, 3.0)}, 8.0, 4.0);
  m.name = "two rooms";
  return m;
}

// Distance between closed segments [a, b] and [c, d].
inline double segment_distance(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
  if (segments_intersect(a, b, c, d)) return 0.0;
  return std::min({distance_to_segment(a, c, d), distance_to_segment(b, c, d),
                   distance_to_segment(c, a, b), distance_to_segment(d, a, b)});
}

// The least distance from a path to any obstacle edge or arena wall; 0 when a
// path vertex lies inside an obstacle.
inline double clearance(const Map& map, const std::vector<Vec2>& path) {
  double best = 1e300;
  for (Vec2 p : path) {
    if (map.obstacle_at(p) >= 0) return 0.0;
    best = std::min({best, p.x, p.y, map.width - p.x, map.height - p.y});
  }
  for (std::size_t k = 0; k + 1 < path.size(); ++k)
    for (const Polygon& poly : map.obstacles)
      for (std::size_t i = 0; i < poly.size(); ++i)
        best = std::min(
            best, segment_distance(path[k], path[k + 1], poly[i], poly[(i + 1) % poly.size()]));
  return best;
}

// Coordinates on a 5 cm lattice, so that obstacles often touch each other or a
// wall exactly, share collinear edges, or leave gaps of exactly 0.3 m.
class MapGenerator {
 public:
  explicit MapGenerator(unsigned seed) : rng_(seed) {}

  double lattice(double lo, double hi) {
    std::uniform_int_distribution<int> k(static_cast<int>(std::ceil(lo * 20 - 1e-9)),
                                         static_cast<int>(std::floor(hi * 20 + 1e-9)));
    return k(rng_) / 20.0;
  }
  double uniform(double lo, double hi) { return std::uniform_real_distribution<>(lo, hi)(rng_); }
  int integer(int lo, int hi) { return std::uniform_int_distribution<>(lo, hi)(rng_); }

  // A valid map (validate_map accepts it) with 1 to 4 obstacles.
  Map next() {
    for (;;) {
      Map m = default_arena();
      const int n = integer(1, 4);
      for (int k = 0; k < n; ++k)
        m.obstacles.push_back(shape());
      try {
        validate_map(m, "random map");
        return m;
      } catch (const InputError&) {
      }
    }
  }

  // A free point of the map (not inside or on an obstacle), on a 1 mm lattice.
  Vec2 free_point(const Map& map) {
    for (;;) {
      const Vec2 p{std::round(uniform(0.0, map.width) * 1000) / 1000,
                   std::round(uniform(0.0, map.height) * 1000) / 1000};
      if (map.obstacle_at(p) < 0) return p;
    }
  }

 private:
  Polygon shape() {
    const int kind = integer(0, 2);
    const double w = lattice(0.3, 2.0), h = lattice(0.3, 2.0);
    double x = lattice(0.0, 10.0 - w), y = lattice(0.0, 4.0 - h);
    if (integer(0, 3) == 0) y = integer(0, 1) ? 4.0 - h : 0.0;  // against a wall
    Polygon p;
    if (kind == 0) {
      p = rect(0, 0, w, h);
    } else {
      const double t = lattice(0.1, std::min(w, h) / 2.0 - 0.05);  // arm thickness
      if (kind == 1)
        p = {{0, 0}, {w, 0}, {w, t}, {t, t}, {t, h}, {0, h}};  // L
      else
        p = {{0, 0}, {w, 0}, {w, t}, {t, t}, {t, h - t}, {w, h - t}, {w, h}, {0, h}};  // U
      // One of four orientations, mirrored inside the bounding box.
      const int turn = integer(0, 3);
      for (Vec2& v : p) {
        if (turn & 1) v.x = w - v.x;
        if (turn & 2) v.y = h - v.y;
      }
      if (turn == 1 || turn == 2) std::reverse(p.begin(), p.end());
    }
    for (Vec2& v : p)
      v = {v.x + x, v.y + y};
    return p;
  }

  std::mt19937 rng_;
};

}  // namespace plumekit::planner::testing
