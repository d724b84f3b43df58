#include "cfd/thin_walls.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <unordered_set>

#include "cfd/gap_closing.hpp"
#include "core/option_check.hpp"

namespace plumekit::cfd {

namespace {

// How much of the axis-parallel segment [a, b] lies inside `poly` (0 when it
// stays outside or on the boundary): the pieces between the points where it
// meets the polygon's edges, each tested at its middle.
double inside_length(const Polygon& poly, Vec2 a, Vec2 b, bool along_x) {
  auto across = [&](Vec2 p) { return along_x ? p.y : p.x; };
  auto along = [&](Vec2 p) { return along_x ? p.x : p.y; };
  const double line = across(a), lo = along(a), hi = along(b);
  std::vector<double> cuts{lo, hi};
  for (std::size_t k = 0; k < poly.size(); ++k) {
    const Vec2 p = poly[k], q = poly[(k + 1) % poly.size()];
    const double dp = across(p) - line, dq = across(q) - line;
    if ((dp > 0 && dq > 0) || (dp < 0 && dq < 0)) continue;
    if (dp == dq) {  // an edge along the line: both its ends
      cuts.push_back(along(p));
      cuts.push_back(along(q));
    } else {
      cuts.push_back(along(p) + (along(q) - along(p)) * dp / (dp - dq));
    }
  }
  for (double& c : cuts)
    c = std::clamp(c, lo, hi);
  std::sort(cuts.begin(), cuts.end());
  double inside = 0.0;
  for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
    if (!(cuts[k + 1] > cuts[k])) continue;
    const double mid = 0.5 * (cuts[k] + cuts[k + 1]);
    if (locate(poly, along_x ? Vec2{mid, line} : Vec2{line, mid}) == Location::Inside)
      inside += cuts[k + 1] - cuts[k];
  }
  return inside;
}

// The pairs of free cells along x (along_x) or y whose link one edge p-q of
// obstacle k crosses, each tested once per obstacle (`seen`).
void edge_leaks(const Map& map, const GridShape& s, const std::vector<std::uint8_t>& solid,
                std::size_t k, Vec2 p, Vec2 q, bool along_x,
                std::unordered_set<std::uint64_t>& seen, ThinWall& wall) {
  auto across = [&](Vec2 v) { return along_x ? v.y : v.x; };
  auto along = [&](Vec2 v) { return along_x ? v.x : v.y; };
  if (across(p) == across(q)) return;  // parallel to the links: its neighbours cross them
  const double h_across = along_x ? s.dy() : s.dx(), h_along = along_x ? s.dx() : s.dy();
  const int n_across = along_x ? s.ny : s.nx, n_along = along_x ? s.nx : s.ny;
  const double lo = std::min(across(p), across(q)), hi = std::max(across(p), across(q));
  const int first = std::max(0, static_cast<int>(std::ceil(lo / h_across - 0.5)));
  const int last = std::min(n_across - 1, static_cast<int>(std::floor(hi / h_across - 0.5)));
  for (int b = first; b <= last; ++b) {
    const double c = (b + 0.5) * h_across;
    const double x = along(p) + (along(q) - along(p)) * (c - across(p)) / (across(q) - across(p));
    const int a = static_cast<int>(std::floor(x / h_along - 0.5));
    if (a < 0 || a + 1 >= n_along) continue;  // between the arena's edge and the first centre
    const std::size_t c0 = along_x ? s.index(a, b) : s.index(b, a);
    const std::size_t c1 = along_x ? s.index(a + 1, b) : s.index(b, a + 1);
    if (solid[c0] || solid[c1]) continue;
    if (!seen.insert(2 * static_cast<std::uint64_t>(c0) + (along_x ? 0 : 1)).second) continue;
    const Vec2 from = along_x ? s.centre(a, b) : s.centre(b, a);
    const Vec2 to = along_x ? s.centre(a + 1, b) : s.centre(b, a + 1);
    const double thick = inside_length(map.obstacles[k], from, to, along_x);
    if (thick <= 0.0) continue;
    if (wall.leaks++ == 0 || thick < wall.thickness) {
      wall.thickness = thick;
      wall.at = 0.5 * (from + to);
    }
  }
}

}  // namespace

std::vector<ThinWall> find_thin_walls(const Map& map, const GridShape& shape,
                                      const std::vector<std::uint8_t>& solid) {
  std::vector<ThinWall> out;
  for (std::size_t k = 0; k < map.obstacles.size(); ++k) {
    const Polygon& poly = map.obstacles[k];
    ThinWall wall;
    wall.obstacle = static_cast<int>(k);
    std::unordered_set<std::uint64_t> seen;
    for (std::size_t v = 0; v < poly.size(); ++v)
      for (const bool along_x : {true, false})
        edge_leaks(map, shape, solid, k, poly[v], poly[(v + 1) % poly.size()], along_x, seen, wall);
    if (wall.leaks > 0) out.push_back(wall);
  }
  return out;
}

ThinWalls summarize_thin_walls(const Map& map, const std::vector<ThinWall>& walls) {
  ThinWalls out;
  double thinnest = std::numeric_limits<double>::infinity();
  for (ThinWall w : walls) {
    thinnest = std::min(thinnest, w.thickness);
    w.at = map.to_frame(w.at);
    out.walls.push_back(w);
  }
  if (!walls.empty()) out.resolving_cell = cell_keeping_gaps_open(map, thinnest);
  return out;
}

std::string thin_walls_text(const ThinWalls& thin, double cell) {
  if (thin.walls.empty()) return "";
  const std::size_t n = thin.walls.size();
  std::ostringstream s;
  s << "the " << compact(cell) << " m cells do not resolve " << n
    << (n == 1 ? " obstacle, so air flows through it" : " obstacles, so air flows through them")
    << " where the planner sees a wall";
  for (std::size_t k = 0; k < n && k < kReportedGaps; ++k) {
    const ThinWall& w = thin.walls[k];
    s << (k == 0 ? ": " : "; ") << "obstacles[" << w.obstacle << "] at ("
      << millimetre_coordinate(w.at.x) << ", " << millimetre_coordinate(w.at.y) << "), "
      << compact(w.thickness) << " m thick (" << w.leaks
      << (w.leaks == 1 ? " cell face" : " cell faces") << " through it)";
  }
  if (n > kReportedGaps) s << "; and " << n - kReportedGaps << " more";
  s << "; a cell of " << compact(thin.resolving_cell) << " m or finer resolves "
    << (n == 1 ? "it" : "them") << ", or thicken the " << (n == 1 ? "wall" : "walls")
    << " in the map";
  return s.str();
}

}  // namespace plumekit::cfd
