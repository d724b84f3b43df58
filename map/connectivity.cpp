#include "map/connectivity.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>
#include <utility>

#include "map/rasterize.hpp"

namespace plumekit {

namespace {

// Floods the region holding (i0, j0), marking it `id` in `owner`; returns its
// cells in flood order.
std::vector<std::pair<int, int>> flood(const Grid<std::uint8_t>& labels, std::vector<int>& owner,
                                       int i0, int j0, int id) {
  const GridShape& s = labels.shape;
  std::vector<std::pair<int, int>> cells{{i0, j0}};
  owner[s.index(i0, j0)] = id;
  for (std::size_t next = 0; next < cells.size(); ++next) {
    const auto [i, j] = cells[next];
    const int di[] = {1, -1, 0, 0}, dj[] = {0, 0, 1, -1};
    for (int k = 0; k < 4; ++k) {
      const int a = i + di[k], b = j + dj[k];
      if (!s.contains(a, b) || owner[s.index(a, b)] >= 0 || labels(a, b) == kObstacle) continue;
      owner[s.index(a, b)] = id;
      cells.emplace_back(a, b);
    }
  }
  return cells;
}

FreeRegion describe(const Grid<std::uint8_t>& labels,
                    const std::vector<std::pair<int, int>>& cells) {
  const GridShape& s = labels.shape;
  FreeRegion r;
  r.cells = static_cast<int>(cells.size());
  r.area_m2 = r.cells * s.dx() * s.dy();
  double ci = 0, cj = 0;
  for (const auto& [i, j] : cells) {
    ci += i;
    cj += j;
    r.inlet = r.inlet || labels(i, j) == kInlet;
    r.outlet = r.outlet || labels(i, j) == kOutlet;
  }
  ci /= r.cells;
  cj /= r.cells;
  double best = std::numeric_limits<double>::infinity();
  for (const auto& [i, j] : cells) {
    const double d = (i - ci) * (i - ci) + (j - cj) * (j - cj);
    if (d < best) {
      best = d;
      r.point = s.centre(i, j);
    }
  }
  return r;
}

std::string area_text(double m2) {
  std::ostringstream s;
  if (m2 >= 100)
    s << std::fixed << std::setprecision(0);
  else
    s << std::setprecision(m2 < 10 ? 2 : 3);
  s << m2 << " m²";
  return s.str();
}

std::string point_text(Vec2 p) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(2) << '(' << p.x << ", " << p.y << ')';
  return s.str();
}

}  // namespace

bool FreeSpace::inlet_reaches_outlet() const {
  for (const FreeRegion& r : regions)
    if (r.inlet && r.outlet) return true;
  return false;
}

FreeSpace free_regions(const Grid<std::uint8_t>& labels) {
  const GridShape& s = labels.shape;
  FreeSpace space;
  std::vector<int> owner(s.size(), -1);
  for (int j = 0; j < s.ny; ++j) {
    for (int i = 0; i < s.nx; ++i) {
      const std::uint8_t l = labels(i, j);
      space.inlet_cells += l == kInlet;
      space.outlet_cells += l == kOutlet;
      if (l == kObstacle || owner[s.index(i, j)] >= 0) continue;
      const auto cells = flood(labels, owner, i, j, static_cast<int>(space.regions.size()));
      space.regions.push_back(describe(labels, cells));
      space.free_area_m2 += space.regions.back().area_m2;
    }
  }
  std::stable_sort(space.regions.begin(), space.regions.end(),
                   [](const FreeRegion& a, const FreeRegion& b) { return a.cells > b.cells; });
  return space;
}

std::vector<MissedOpening> openings_missed_by_grid(const Map& map, const GridShape& shape) {
  std::vector<MissedOpening> out;
  for (std::size_t k = 0; k < map.openings.size(); ++k) {
    const Opening& o = map.openings[k];
    const double h = o.vertical() ? shape.dy() : shape.dx();
    const int n = o.vertical() ? shape.ny : shape.nx;
    // The face middles nearest the span's start, computed as the grid does.
    const int first = std::max(0, static_cast<int>(std::floor(o.lo() / h - 0.5)));
    bool seen = false;
    for (int b = first; b < n && b <= first + 2 && !seen; ++b) {
      const double s = (b + 0.5) * h;
      seen = s >= o.lo() && s <= o.hi();
    }
    if (!seen) out.push_back({k, o.length(), h});
  }
  std::stable_sort(out.begin(), out.end(), [](const MissedOpening& a, const MissedOpening& b) {
    return a.length < b.length;
  });
  return out;
}

std::string opening_name(const Map& map, std::size_t k) {
  const Opening& o = map.openings[k];
  if (map.format_version == 1) return o.is_inlet() ? "the inlet" : "the outlet";
  return "openings[" + std::to_string(k) + "] (an " + to_string(o.kind) + ")";
}

std::vector<bool> in_sealed_pocket(const Grid<std::uint8_t>& labels,
                                   const std::vector<Vec2>& points) {
  const GridShape& s = labels.shape;
  // Every free cell that some opening's cell reaches.
  std::vector<int> owner(s.size(), -1);
  for (int j = 0; j < s.ny; ++j)
    for (int i = 0; i < s.nx; ++i)
      if ((labels(i, j) == kInlet || labels(i, j) == kOutlet) && owner[s.index(i, j)] < 0)
        flood(labels, owner, i, j, 0);
  std::vector<bool> sealed;
  for (const Vec2 p : points) {
    const int i = std::clamp(static_cast<int>(std::floor(p.x / s.dx())), 0, s.nx - 1);
    const int j = std::clamp(static_cast<int>(std::floor(p.y / s.dy())), 0, s.ny - 1);
    // The point's own cell, or the free cells around it when that one is solid
    // (a point less than half a cell off an obstacle).
    const int reach = labels(i, j) == kObstacle ? 1 : 0;
    bool free = false, reached = false;
    for (int b = j - reach; b <= j + reach; ++b)
      for (int a = i - reach; a <= i + reach; ++a) {
        if (!s.contains(a, b) || labels(a, b) == kObstacle) continue;
        free = true;
        reached = reached || owner[s.index(a, b)] >= 0;
      }
    sealed.push_back(free && !reached);
  }
  return sealed;
}

std::vector<std::string> sealed_map_advice(const Map& map, const FreeSpace& space,
                                           bool unknown_hint, bool opening_fields) {
  if (space.inlet_reaches_outlet()) return {};
  const std::string add =
      opening_fields ? "add openings on its boundary with ros.inlets / ros.outlets (map frame)"
                     : "move or add openings (the file's \"openings\") onto its boundary";
  std::vector<std::string> out;
  out.push_back("no free path from any inlet to any outlet: the map cannot carry a flow");
  if (space.inlet_cells == 0)
    out.push_back("no inlet opens into free space: every cell beside the inlets is occupied");
  if (space.outlet_cells == 0)
    out.push_back("no outlet opens into free space: every cell beside the outlets is occupied");
  for (const FreeRegion& r : space.regions) {
    if (r.inlet == r.outlet) continue;
    out.push_back(std::string("the free region the ") + (r.inlet ? "inlets open" : "outlets open") +
                  " into (" + area_text(r.area_m2) + " around " +
                  point_text(map.to_frame(r.point)) + ") has no " + (r.inlet ? "outlet" : "inlet") +
                  "; " + add);
    break;  // the largest one says enough
  }
  for (const FreeRegion& r : space.regions) {
    if (r.inlet || r.outlet) continue;
    std::ostringstream share;
    const double percent = 100.0 * r.area_m2 / space.free_area_m2;
    share << std::fixed << std::setprecision(percent >= 10 ? 0 : 1) << percent;
    out.push_back("the largest sealed free region (" + area_text(r.area_m2) + ", " + share.str() +
                  " % of the free space, around " + point_text(map.to_frame(r.point)) +
                  ") touches no opening; " + add);
    break;
  }
  if (unknown_hint)
    out.push_back(
        "unknown (unexplored) space counts as occupied; import with ros.unknown free "
        "to make it open air, so that doors leading into it connect to the arena's "
        "walls (the default inlet and outlet)");
  return out;
}

}  // namespace plumekit
