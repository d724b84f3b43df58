#include "dataset/building_maps.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>
#include <vector>

#include "core/error.hpp"
#include "core/random.hpp"
#include "map/map_json.hpp"
#include "map/rasterize.hpp"

namespace plumekit::dataset {

namespace {

// Plans are laid out in integer ticks of 0.1 m: comparisons are exact and every
// coordinate written is ticks / 10, the double nearest a multiple of 0.1 m.
constexpr int kTicksPerMetre = 10;
constexpr int kOuterWall = 2;   // 0.2 m: outer walls
constexpr int kInnerWall = 1;   // 0.1 m: interior walls
constexpr int kMinRoom = 24;    // 2.4 m: the narrowest room
constexpr int kJamb = 2;        // wall kept between a door or opening and a corner or junction
constexpr int kOpeningGap = 3;  // between two openings on one wall
constexpr int kMinDoor = 9;     // 0.9 m: doors are 0.9-1.2 m, or wider when the passage is

double metres(int ticks) {
  return static_cast<double>(ticks) / kTicksPerMetre;
}

struct IBox {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  int w() const { return x1 - x0; }
  int h() const { return y1 - y0; }
  bool within(const IBox& o) const { return x0 >= o.x0 && x1 <= o.x1 && y0 >= o.y0 && y1 <= o.y1; }
};

// The Euclidean gap between two boxes, 0 when they touch or overlap.
double gap(const IBox& a, const IBox& b) {
  const int dx = std::max({0, b.x0 - a.x1, a.x0 - b.x1});
  const int dy = std::max({0, b.y0 - a.y1, a.y0 - b.y1});
  return std::hypot(dx, dy);
}

class Dice {
 public:
  explicit Dice(std::mt19937_64& rng) : rng_(rng) {}
  // A uniform integer in [lo, hi]; lo when hi <= lo.
  int between(int lo, int hi) {
    if (hi <= lo) return lo;
    return lo + std::min(hi - lo, static_cast<int>(uniform(rng_, 0.0, hi - lo + 1.0)));
  }
  bool chance(double p) { return uniform01(rng_) < p; }

 private:
  std::mt19937_64& rng_;
};

struct OuterOpening {
  Side side = Side::Left;
  int from = 0, to = 0;  // ticks along the wall
  bool door = false;     // a gap in the outer wall, else a window in its inner face
  OpeningKind kind = OpeningKind::Inlet;
};

// A room's stretch of outer wall, where an opening may go.
struct Stretch {
  Side side;
  int lo, hi;  // ticks along the wall
};

struct Plan {
  int width = 0, height = 0;  // ticks
  int passage = 8;            // ticks: the narrowest door, corridor or gap by furniture
  IBox interior;              // inside the outer walls
  std::vector<IBox> walls;    // before the doors are cut
  std::vector<IBox> doors;    // gaps through a wall's whole thickness
  std::vector<IBox> rooms;    // free rectangles, the corridor included
  int corridor = -1;          // index in rooms
  std::vector<OuterOpening> openings;
  std::vector<IBox> furniture;
};

// A box given along / across an axis: along x when along_x, else transposed.
IBox oriented(bool along_x, int a0, int b0, int a1, int b1) {
  return along_x ? IBox{a0, b0, a1, b1} : IBox{b0, a0, b1, a1};
}

int door_width(Dice& d, int passage) {
  const int lo = std::max(passage, kMinDoor);
  return d.between(lo, lo + 3);
}

// A door of `width` in `wall` (running along x when along_x), kJamb from its ends.
bool add_door(Plan& p, Dice& d, const IBox& wall, bool along_x, int width) {
  const int lo = (along_x ? wall.x0 : wall.y0) + kJamb;
  const int hi = (along_x ? wall.x1 : wall.y1) - kJamb - width;
  if (hi < lo) return false;
  const int s = d.between(lo, hi);
  p.doors.push_back(along_x ? IBox{s, wall.y0, s + width, wall.y1}
                            : IBox{wall.x0, s, wall.x1, s + width});
  return true;
}

// Long floors usually get a corridor along their long axis, as long as the
// floor, with a row of rooms on each side, each with its own door onto it.
// The rooms go to `pending` to be split further.
bool lay_out_corridor(Plan& p, Dice& d, std::vector<IBox>& pending) {
  const IBox& in = p.interior;
  const bool along_x = in.w() >= in.h();
  const int a0 = along_x ? in.x0 : in.y0, a1 = along_x ? in.x1 : in.y1;
  const int b0 = along_x ? in.y0 : in.x0, b1 = along_x ? in.y1 : in.x1;
  const int wide = std::max(p.passage, 12);
  const int cw = d.between(wide, wide + 8);
  const int row = kMinRoom + kInnerWall;
  if (a1 - a0 < 80 || b1 - b0 < 2 * row + cw || !d.chance(0.75)) return false;
  const int c0 = d.between(b0 + row, b1 - row - cw), c1 = c0 + cw;
  p.corridor = static_cast<int>(p.rooms.size());
  p.rooms.push_back(oriented(along_x, a0, c0, a1, c1));
  const std::pair<int, int> rows[2] = {{b0, c0 - kInnerWall}, {c1 + kInnerWall, b1}};
  for (const auto& [r0, r1] : rows) {
    const bool below = r1 == c0 - kInnerWall;
    const IBox corridor_wall =
        below ? oriented(along_x, a0, r1, a1, c0) : oriented(along_x, a0, c1, a1, r0);
    p.walls.push_back(corridor_wall);
    for (int a = a0; a < a1;) {
      int w = d.between(kMinRoom, 60);
      if (a1 - a - w - kInnerWall < kMinRoom) w = a1 - a;
      const IBox room = oriented(along_x, a, r0, a + w, r1);
      const IBox door_stretch =
          below ? oriented(along_x, a, r1, a + w, c0) : oriented(along_x, a, c1, a + w, r0);
      add_door(p, d, door_stretch, along_x, door_width(d, p.passage));
      if (a + w < a1) p.walls.push_back(oriented(along_x, a + w, r0, a + w + kInnerWall, r1));
      pending.push_back(room);
      a += w + kInnerWall;
    }
  }
  return true;
}

// Splits `room` by a wall with a door across its longer side, leaving kMinRoom
// on both sides and keeping kJamb from every door; nullopt when no place does.
std::optional<std::pair<IBox, IBox>> split_room(Plan& p, Dice& d, const IBox& room) {
  const bool cut_x = room.w() >= room.h();  // a wall at some x, running along y
  const int lo = (cut_x ? room.x0 : room.y0) + kMinRoom;
  const int hi = (cut_x ? room.x1 : room.y1) - kMinRoom - kInnerWall;
  if (hi < lo) return std::nullopt;
  for (int attempt = 0; attempt < 10; ++attempt) {
    const int c = d.between(lo, hi);
    const IBox wall = cut_x ? IBox{c, room.y0, c + kInnerWall, room.y1}
                            : IBox{room.x0, c, room.x1, c + kInnerWall};
    const bool clear = std::all_of(p.doors.begin(), p.doors.end(),
                                   [&](const IBox& door) { return gap(wall, door) >= kJamb; });
    if (!clear) continue;
    if (!add_door(p, d, wall, !cut_x, door_width(d, p.passage))) continue;
    p.walls.push_back(wall);
    if (cut_x)
      return std::make_pair(IBox{room.x0, room.y0, c, room.y1},
                            IBox{c + kInnerWall, room.y0, room.x1, room.y1});
    return std::make_pair(IBox{room.x0, room.y0, room.x1, c},
                          IBox{room.x0, c + kInnerWall, room.x1, room.y1});
  }
  return std::nullopt;
}

// Rooms longer than a drawn 5-9 m are split in two, recursively.
void split_rooms(Plan& p, Dice& d, std::vector<IBox> pending) {
  for (std::size_t k = 0; k < pending.size(); ++k) {
    const IBox room = pending[k];
    const int longest = d.between(50, 90);
    std::optional<std::pair<IBox, IBox>> halves;
    if (std::max(room.w(), room.h()) > longest) halves = split_room(p, d, room);
    if (halves) {
      pending.push_back(halves->first);
      pending.push_back(halves->second);
    } else {
      p.rooms.push_back(room);
    }
  }
}

std::vector<Stretch> outer_stretches(const Plan& p) {
  std::vector<Stretch> out;
  const IBox& in = p.interior;
  for (const IBox& r : p.rooms) {
    if (r.x0 == in.x0) out.push_back({Side::Left, r.y0, r.y1});
    if (r.x1 == in.x1) out.push_back({Side::Right, r.y0, r.y1});
    if (r.y0 == in.y0) out.push_back({Side::Bottom, r.x0, r.x1});
    if (r.y1 == in.y1) out.push_back({Side::Top, r.x0, r.x1});
  }
  return out;
}

// The gap a door cuts through the outer wall on `side`, [from, to] along it.
IBox outer_gap(const Plan& p, Side side, int from, int to) {
  switch (side) {
    case Side::Left:
      return {0, from, kOuterWall, to};
    case Side::Right:
      return {p.width - kOuterWall, from, p.width, to};
    case Side::Bottom:
      return {from, 0, to, kOuterWall};
    case Side::Top:
      break;
  }
  return {from, p.height - kOuterWall, to, p.height};
}

// One door or window of `kind` on some room's outer wall, on another side than
// `avoid` where there is one; false when none fits.
bool place_opening(Plan& p, Dice& d, OpeningKind kind, std::optional<Side> avoid) {
  std::vector<Stretch> all = outer_stretches(p), other;
  for (const Stretch& s : all)
    if (s.side != avoid) other.push_back(s);
  const std::vector<Stretch>& pool = other.empty() ? all : other;
  const bool door = d.chance(0.5);
  const int width = door ? door_width(d, p.passage) : d.between(6, 20);
  for (int attempt = 0; attempt < 20; ++attempt) {
    const Stretch& s = pool[static_cast<std::size_t>(d.between(0, int(pool.size()) - 1))];
    const int at = d.between(s.lo + kJamb, s.hi - kJamb - width);
    if (at + width > s.hi - kJamb) continue;
    const bool apart = std::all_of(p.openings.begin(), p.openings.end(), [&](const auto& o) {
      return o.side != s.side || at >= o.to + kOpeningGap || at + width + kOpeningGap <= o.from;
    });
    if (!apart) continue;
    p.openings.push_back({s.side, at, at + width, door, kind});
    if (door) p.doors.push_back(outer_gap(p, s.side, at, at + width));
    return true;
  }
  return false;
}

// One to three inlets and outlets (1, 2, 3 with odds 3:2:1); the first outlet
// on another wall than the first inlet. False when the first ones do not fit.
bool place_openings(Plan& p, Dice& d) {
  const int counts[6] = {1, 1, 1, 2, 2, 3};
  const int inlets = counts[d.between(0, 5)], outlets = counts[d.between(0, 5)];
  if (!place_opening(p, d, OpeningKind::Inlet, std::nullopt)) return false;
  if (!place_opening(p, d, OpeningKind::Outlet, p.openings[0].side)) return false;
  for (int k = 1; k < inlets; ++k)
    place_opening(p, d, OpeningKind::Inlet, std::nullopt);
  for (int k = 1; k < outlets; ++k)
    place_opening(p, d, OpeningKind::Outlet, std::nullopt);
  return true;
}

// What furniture keeps a passage away from: doors (inside and out) and windows.
std::vector<IBox> keep_clear(const Plan& p) {
  std::vector<IBox> out = p.doors;
  for (const OuterOpening& o : p.openings) {
    if (o.door) continue;
    IBox b = outer_gap(p, o.side, o.from, o.to);
    // The window's line: the outer wall's inner face.
    if (o.side == Side::Left) b.x0 = b.x1;
    if (o.side == Side::Right) b.x1 = b.x0;
    if (o.side == Side::Bottom) b.y0 = b.y1;
    if (o.side == Side::Top) b.y1 = b.y0;
    out.push_back(b);
  }
  return out;
}

// A piece of furniture (0.4-2.0 x 0.4-1.2 m) in `room`, against a wall or
// free-standing: every gap it leaves to a wall is 0 or at least a passage, and
// it keeps a passage from doors, windows and the room's other furniture.
std::optional<IBox> draw_furniture(const Plan& p, Dice& d, const IBox& room,
                                   const std::vector<IBox>& clear, std::size_t first) {
  int a = d.between(4, 20), b = d.between(4, 12);
  if (d.chance(0.5)) std::swap(a, b);
  const int mode = d.between(0, 4);  // free-standing, or against the left/right/bottom/top wall
  int x0 = d.between(room.x0, room.x1 - a), y0 = d.between(room.y0, room.y1 - b);
  if (mode == 1) x0 = room.x0;
  if (mode == 2) x0 = room.x1 - a;
  if (mode == 3) y0 = room.y0;
  if (mode == 4) y0 = room.y1 - b;
  const IBox f{x0, y0, x0 + a, y0 + b};
  if (!f.within(room)) return std::nullopt;
  for (int g : {f.x0 - room.x0, room.x1 - f.x1, f.y0 - room.y0, room.y1 - f.y1})
    if (g != 0 && g < p.passage) return std::nullopt;
  for (const IBox& c : clear)
    if (gap(f, c) < p.passage) return std::nullopt;
  for (std::size_t k = first; k < p.furniture.size(); ++k)
    if (gap(f, p.furniture[k]) < p.passage) return std::nullopt;
  return f;
}

// Up to one piece per 8 m^2 (at most 6) in every room but the corridor.
void furnish(Plan& p, Dice& d) {
  const std::vector<IBox> clear = keep_clear(p);
  for (std::size_t r = 0; r < p.rooms.size(); ++r) {
    if (static_cast<int>(r) == p.corridor) continue;
    const IBox& room = p.rooms[r];
    const std::size_t first = p.furniture.size();
    const int count = d.between(0, std::min(6, 1 + room.w() * room.h() / 800));
    for (int k = 0; k < count; ++k)
      for (int attempt = 0; attempt < 30; ++attempt)
        if (const auto f = draw_furniture(p, d, room, clear, first)) {
          p.furniture.push_back(*f);
          break;
        }
  }
}

Polygon rectangle(const IBox& b) {
  return {{metres(b.x0), metres(b.y0)},
          {metres(b.x1), metres(b.y0)},
          {metres(b.x1), metres(b.y1)},
          {metres(b.x0), metres(b.y1)}};
}

// The walls with their doors cut out, as rectangles.
std::vector<IBox> wall_pieces(const Plan& p) {
  std::vector<IBox> out;
  for (const IBox& wall : p.walls) {
    const bool along_x = wall.w() > wall.h();
    std::vector<std::pair<int, int>> cuts;
    for (const IBox& door : p.doors)
      if (door.within(wall))
        cuts.emplace_back(along_x ? door.x0 : door.y0, along_x ? door.x1 : door.y1);
    std::sort(cuts.begin(), cuts.end());
    int at = along_x ? wall.x0 : wall.y0;
    cuts.emplace_back(along_x ? wall.x1 : wall.y1, 0);
    for (const auto& [lo, hi] : cuts) {
      if (lo > at)
        out.push_back(along_x ? IBox{at, wall.y0, lo, wall.y1} : IBox{wall.x0, at, wall.x1, lo});
      at = std::max(at, hi);
    }
  }
  return out;
}

Opening to_opening(const Plan& p, const OuterOpening& o, double speed) {
  // Doors open on the arena wall, windows on the outer wall's inner face.
  const int depth = o.door ? 0 : kOuterWall;
  Opening out;
  out.kind = o.kind;
  out.speed = o.kind == OpeningKind::Inlet ? speed : 1.0;
  switch (o.side) {
    case Side::Left:
      out.from = {metres(depth), metres(o.from)}, out.to = {metres(depth), metres(o.to)};
      break;
    case Side::Right:
      out.from = {metres(p.width - depth), metres(o.from)};
      out.to = {metres(p.width - depth), metres(o.to)};
      break;
    case Side::Bottom:
      out.from = {metres(o.from), metres(depth)}, out.to = {metres(o.to), metres(depth)};
      break;
    case Side::Top:
      out.from = {metres(o.from), metres(p.height - depth)};
      out.to = {metres(o.to), metres(p.height - depth)};
      break;
  }
  return out;
}

Map to_map(const Plan& p, const RandomMapOptions& o, const std::string& name) {
  Map map;
  map.name = name;
  map.format_version = 2;
  map.width = metres(p.width);
  map.height = metres(p.height);
  for (const IBox& b : wall_pieces(p))
    map.obstacles.push_back(rectangle(b));
  for (const IBox& b : p.furniture)
    map.obstacles.push_back(rectangle(b));
  for (const OuterOpening& op : p.openings)
    map.openings.push_back(to_opening(p, op, o.inlet_speed));
  return map;
}

int ticks(double metres_value, bool round_up) {
  const double t = metres_value * kTicksPerMetre;
  return static_cast<int>(round_up ? std::ceil(t - 1e-9) : std::floor(t + 1e-9));
}

// One draw of a floor plan; nullopt when its first inlet or outlet does not fit.
std::optional<Map> draw_building(const RandomMapOptions& o, Dice& d, const std::string& name) {
  Plan p;
  const int lo = ticks(o.building_min_size, true), hi = ticks(o.building_max_size, false);
  p.width = d.between(lo, hi);
  p.height = d.between(lo, hi);
  p.passage = ticks(o.building_passage, true);
  p.interior = {kOuterWall, kOuterWall, p.width - kOuterWall, p.height - kOuterWall};
  const int w = p.width, h = p.height;
  p.walls = {{0, 0, kOuterWall, h},
             {w - kOuterWall, 0, w, h},
             {kOuterWall, 0, w - kOuterWall, kOuterWall},
             {kOuterWall, h - kOuterWall, w - kOuterWall, h}};
  std::vector<IBox> pending;
  if (!lay_out_corridor(p, d, pending)) pending = {p.interior};
  split_rooms(p, d, pending);
  if (!place_openings(p, d)) return std::nullopt;
  furnish(p, d);
  return to_map(p, o, name);
}

std::vector<std::uint8_t> flood(const GridShape& g, const std::vector<std::uint8_t>& open,
                                std::size_t start) {
  std::vector<std::uint8_t> seen(g.size(), 0);
  std::vector<std::size_t> stack{start};
  seen[start] = 1;
  while (!stack.empty()) {
    const std::size_t k = stack.back();
    stack.pop_back();
    const int i = static_cast<int>(k % g.nx), j = static_cast<int>(k / g.nx);
    const int di[4] = {1, -1, 0, 0}, dj[4] = {0, 0, 1, -1};
    for (int n = 0; n < 4; ++n) {
      const int a = i + di[n], b = j + dj[n];
      if (!g.contains(a, b)) continue;
      const std::size_t m = g.index(a, b);
      if (!open[m] || seen[m]) continue;
      seen[m] = 1;
      stack.push_back(m);
    }
  }
  return seen;
}

// Whether the cells marked open form one 4-connected, non-empty region.
bool one_region(const GridShape& g, const std::vector<std::uint8_t>& open) {
  const auto first = std::find(open.begin(), open.end(), std::uint8_t{1});
  if (first == open.end()) return false;
  const std::vector<std::uint8_t> seen =
      flood(g, open, static_cast<std::size_t>(first - open.begin()));
  return std::count(seen.begin(), seen.end(), 1) == std::count(open.begin(), open.end(), 1);
}

// Marks closed every cell whose centre lies within `radius` of segment [a, b].
void close_near(const GridShape& g, Vec2 a, Vec2 b, double radius,
                std::vector<std::uint8_t>& open) {
  const int i0 = std::max(0, static_cast<int>(std::floor((std::min(a.x, b.x) - radius) / g.dx())));
  const int i1 = std::min(g.nx - 1, static_cast<int>((std::max(a.x, b.x) + radius) / g.dx()));
  const int j0 = std::max(0, static_cast<int>(std::floor((std::min(a.y, b.y) - radius) / g.dy())));
  const int j1 = std::min(g.ny - 1, static_cast<int>((std::max(a.y, b.y) + radius) / g.dy()));
  for (int j = j0; j <= j1; ++j)
    for (int i = i0; i <= i1; ++i)
      if (distance_to_segment(g.centre(i, j), a, b) < radius) open[g.index(i, j)] = 0;
}

// The solid stretches of the arena's walls: each wall less its openings.
std::vector<std::pair<Vec2, Vec2>> solid_walls(const Map& map) {
  std::vector<std::pair<Vec2, Vec2>> out;
  for (Side side : {Side::Left, Side::Right, Side::Bottom, Side::Top}) {
    std::vector<std::pair<double, double>> spans;
    for (const Opening& o : map.openings)
      if (map.wall_of(o) == side) spans.emplace_back(o.lo(), o.hi());
    std::sort(spans.begin(), spans.end());
    double at = 0.0;
    spans.emplace_back(map.wall_length(side), map.wall_length(side));
    for (const auto& [lo, hi] : spans) {
      if (lo > at) out.emplace_back(map.wall_point(side, at), map.wall_point(side, lo));
      at = std::max(at, hi);
    }
  }
  return out;
}

}  // namespace

bool openings_open(const Map& map, double cell) {
  for (const Opening& o : map.openings) {
    const Vec2 n = map.inward_normal(o);
    const int steps = std::max(1, static_cast<int>(std::ceil(o.length() / cell)));
    for (int k = 0; k < steps; ++k) {
      const double s = o.lo() + (k + 0.5) * o.length() / steps;
      const Vec2 at = o.vertical() ? Vec2{o.line(), s} : Vec2{s, o.line()};
      if (!map.is_free(at + 0.5 * cell * n)) return false;
    }
  }
  return true;
}

bool free_space_connected(const Map& map, double cell) {
  const Grid<std::uint8_t> labels =
      rasterize_labels(map, GridShape::with_cell(map.width, map.height, cell));
  std::vector<std::uint8_t> open(labels.values.size());
  for (std::size_t k = 0; k < open.size(); ++k)
    open[k] = labels.values[k] != kObstacle;
  return one_region(labels.shape, open);
}

bool robot_region_connected(const Map& map, double radius, double cell) {
  const GridShape g = GridShape::with_cell(map.width, map.height, cell);
  std::vector<std::uint8_t> open(g.size(), 1);
  for (const Polygon& poly : map.obstacles) {
    for (std::size_t k = 0; k < poly.size(); ++k)
      close_near(g, poly[k], poly[(k + 1) % poly.size()], radius, open);
    // Deep inside a large obstacle is farther than `radius` from its edges.
    const Box b = bounding_box(poly);
    const int i0 = std::max(0, static_cast<int>(b.lo.x / g.dx()));
    const int i1 = std::min(g.nx - 1, static_cast<int>(b.hi.x / g.dx()));
    const int j0 = std::max(0, static_cast<int>(b.lo.y / g.dy()));
    const int j1 = std::min(g.ny - 1, static_cast<int>(b.hi.y / g.dy()));
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i)
        if (covers(poly, g.centre(i, j))) open[g.index(i, j)] = 0;
  }
  for (const auto& [a, b] : solid_walls(map))
    close_near(g, a, b, radius, open);
  return one_region(g, open);
}

std::string building_fault(const Map& map, const RandomMapOptions& o, double cell) {
  try {
    validate_map(map, map.name);
  } catch (const InputError& e) {
    return std::string("it does not validate: ") + e.what();
  }
  const double eps = 1e-9;
  for (double side : {map.width, map.height})
    if (side < o.building_min_size - eps || side > o.building_max_size + eps)
      return "a side is outside maps.building_min_size..maps.building_max_size";
  if (!openings_open(map, cell)) return "an opening is blocked";
  if (!free_space_connected(map, cell)) return "the free space is not one region";
  const GridShape g = GridShape::with_cell(map.width, map.height, cell);
  if (!inlet_reaches_outlet(rasterize_labels(map, g))) return "no inlet reaches an outlet";
  if (!robot_region_connected(map, 0.5 * o.building_passage - cell, cell))
    return "a door or corridor is narrower than maps.building_passage";
  return "";
}

RandomMap random_building(const RandomMapOptions& o, std::mt19937_64& rng,
                          const std::string& name) {
  Dice d(rng);
  RandomMap r;
  r.family = "building";
  for (r.attempts = 1; r.attempts <= o.max_attempts; ++r.attempts) {
    std::optional<Map> map = draw_building(o, d, name);
    if (map && building_fault(*map, o).empty()) {
      r.map = std::move(*map);
      return r;
    }
  }
  throw InputError(
      "random maps: no acceptable building in " + std::to_string(o.max_attempts) +
      " draws; use a smaller maps.building_passage or a larger maps.building_min_size");
}

}  // namespace plumekit::dataset
