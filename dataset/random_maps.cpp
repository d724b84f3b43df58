#include "dataset/random_maps.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <random>
#include <vector>

#include "cfd/options.hpp"
#include "cfd/staggered_grid.hpp"
#include "core/error.hpp"
#include "core/option_check.hpp"
#include "core/seed.hpp"
#include "dataset/building_maps.hpp"
#include "dataset/option_tables.hpp"
#include "map/map_json.hpp"
#include "map/rasterize.hpp"
#include "surrogate/features.hpp"

namespace plumekit::dataset {

double unit_uniform(std::uint64_t bits) {
  return static_cast<double>(bits >> 11) * 0x1.0p-53;
}

namespace {

class Draw {
 public:
  explicit Draw(std::uint64_t seed) : rng_(seed) {}
  double uniform(double a, double b) { return a + (b - a) * unit_uniform(rng_()); }
  int pick(int n) { return std::min(n - 1, static_cast<int>(uniform(0.0, n))); }
  std::mt19937_64& engine() { return rng_; }

 private:
  std::mt19937_64 rng_;
};

// A shape in local coordinates [0, w] x [0, h], turned by quarter turns and
// placed with its bounding box's lower-left corner at `at`.
Polygon place(const Polygon& local, double w, double h, int quarter_turns, Vec2 at) {
  Polygon out;
  for (Vec2 p : local) {
    Vec2 q = p;
    switch (quarter_turns & 3) {
      case 1:
        q = {h - p.y, p.x};
        break;
      case 2:
        q = {w - p.x, h - p.y};
        break;
      case 3:
        q = {p.y, w - p.x};
        break;
      default:
        break;
    }
    out.push_back(q + at);
  }
  return out;
}

// Bounding box size after the turns.
std::pair<double, double> turned(double w, double h, int turns) {
  return (turns & 1) ? std::make_pair(h, w) : std::make_pair(w, h);
}

// Where a box of height bh goes: on the floor, hanging from the ceiling, or
// floating with at least min_gap above and below.
double place_y(Draw& d, double bh, const RandomMapOptions& o) {
  const int mode = d.pick(3);
  if (mode == 0) return 0.0;
  if (mode == 1) return o.height - bh;
  const double lo = o.min_gap, hi = o.height - bh - o.min_gap;
  return hi > lo ? d.uniform(lo, hi) : 0.0;
}

double place_x(Draw& d, double bw, const RandomMapOptions& o) {
  return d.uniform(o.end_clearance, std::max(o.end_clearance, o.width - o.end_clearance - bw));
}

double polygon_distance(const Polygon& a, const Polygon& b) {
  double d = 1e300;
  for (std::size_t i = 0; i < a.size(); ++i)
    for (std::size_t k = 0; k < b.size(); ++k) {
      const Vec2 a0 = a[i], a1 = a[(i + 1) % a.size()], b0 = b[k], b1 = b[(k + 1) % b.size()];
      if (segments_intersect(a0, a1, b0, b1)) return 0.0;
      d = std::min({d, distance_to_segment(a0, b0, b1), distance_to_segment(a1, b0, b1),
                    distance_to_segment(b0, a0, a1), distance_to_segment(b1, a0, a1)});
    }
  return d;
}

Polygon draw_obstacle(Draw& d, const std::string& family, const RandomMapOptions& o) {
  if (family == "l-shape" || family == "u-shape") {
    const bool u = family == "u-shape";
    const double w = d.uniform(u ? 0.9 : 0.8, 2.0), h = d.uniform(u ? 0.9 : 0.8, 2.6);
    const double t = d.uniform(0.2, u ? 0.35 : 0.5);
    const int turns = d.pick(4);
    Polygon local;
    if (u)
      local = {{0, 0}, {w, 0}, {w, h}, {w - t, h}, {w - t, t}, {t, t}, {t, h}, {0, h}};
    else
      local = {{0, 0}, {w, 0}, {w, t}, {t, t}, {t, h}, {0, h}};
    const auto [bw, bh] = turned(w, h, turns);
    return place(local, w, h, turns, {place_x(d, bw, o), place_y(d, bh, o)});
  }
  const double w = d.uniform(0.3, 1.5), h = d.uniform(0.4, 2.6);
  return place({{0, 0}, {w, 0}, {w, h}, {0, h}}, w, h, 0, {place_x(d, w, o), place_y(d, h, o)});
}

bool acceptable(const Map& map, const RandomMapOptions& o) {
  try {
    validate_map(map, map.name);
  } catch (const InputError&) {
    return false;
  }
  for (std::size_t a = 0; a < map.obstacles.size(); ++a) {
    const Box b = bounding_box(map.obstacles[a]);
    // Touching the floor or ceiling is fine; a slit under or over is not.
    const double below = b.lo.y, above = map.height - b.hi.y;
    if ((below > 0.0 && below < o.min_gap) || (above > 0.0 && above < o.min_gap)) return false;
    for (std::size_t c = a + 1; c < map.obstacles.size(); ++c)
      if (polygon_distance(map.obstacles[a], map.obstacles[c]) < o.min_gap) return false;
  }
  const GridShape flow = GridShape::with_cell(map.width, map.height, 0.05);
  if (!inlet_reaches_outlet(rasterize_labels(map, flow))) return false;
  return robot_can_cross(map, o.robot_margin);
}

}  // namespace

std::vector<std::string> RandomMapOptions::known_families() {
  std::vector<std::string> all = thesis_families();
  all.push_back("three-rectangles");
  all.push_back("shape-and-rectangle");
  all.push_back("building");
  return all;
}

bool robot_can_cross(const Map& map, double margin) {
  const GridShape g = GridShape::with_cell(map.width, map.height, 0.05);
  std::vector<std::uint8_t> ok(g.size(), 0), seen(g.size(), 0);
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i)
      ok[g.index(i, j)] = surrogate::signed_distance(map, g.centre(i, j)) >= margin;
  std::vector<std::pair<int, int>> stack;
  for (int j = 0; j < g.ny; ++j)
    if (ok[g.index(0, j)]) {
      stack.emplace_back(0, j);
      seen[g.index(0, j)] = 1;
    }
  while (!stack.empty()) {
    const auto [i, j] = stack.back();
    stack.pop_back();
    if (i == g.nx - 1) return true;
    const int di[4] = {1, -1, 0, 0}, dj[4] = {0, 0, 1, -1};
    for (int k = 0; k < 4; ++k) {
      const int a = i + di[k], b = j + dj[k];
      if (!g.contains(a, b) || !ok[g.index(a, b)] || seen[g.index(a, b)]) continue;
      seen[g.index(a, b)] = 1;
      stack.emplace_back(a, b);
    }
  }
  return false;
}

std::string family_of(const std::string& name) {
  // Longest first: "rectangle" is also the tail of the others.
  for (const char* f : {"shape-and-rectangle", "three-rectangles", "two-rectangles", "rectangle",
                        "l-shape", "u-shape", "building"}) {
    const std::string tail = std::string("-") + f;
    if (name.size() >= tail.size() &&
        name.compare(name.size() - tail.size(), tail.size(), tail) == 0)
      return f;
  }
  return "";
}

const OptionTable<RandomMapOptions>& random_map_option_table() {
  using O = RandomMapOptions;
  // At most 100 m: the robot check and the building's checks rasterize the arena at 5 cm.
  static const OptionTable<O> table{
      "Random maps (dataset::RandomMapOptions)",
      {{"maps.width", "--width", &O::width, positive(100.0, "m"), "Arena width, m"},
       {"maps.height", "--height", &O::height, positive(100.0, "m"), "Arena height, m"},
       {"maps.min_gap", "--min-gap", &O::min_gap, positive(100.0, "m"), "Narrowest passage, m"},
       {"maps.building_min_size", "--building-min-size", &O::building_min_size,
        real_range(4.0, 100.0, "m"), "building: smallest side of a floor, m",
        "the default is {default} m; a floor needs outer walls, a room and a door"},
       {"maps.building_max_size", "--building-max-size", &O::building_max_size,
        real_range(4.0, 100.0, "m"), "building: largest side of a floor, m"},
       {"maps.building_passage", "--building-passage", &O::building_passage,
        real_range(0.3, 1.5, "m"), "building: narrowest door, corridor or gap by furniture, m",
        "the default is {default} m: a door a robot passes"},
       {"maps.robot_margin", "--margin", &O::robot_margin, non_negative(10.0, "m"),
        "Robot radius + safety that must pass from inlet to outlet, m"},
       {"maps.inlet_speed", "", &O::inlet_speed, positive(kMaxInletSpeed, "m/s"),
        "Inlet speed, uniform over the whole left wall, m/s",
        std::string("the default is {default} m/s; ") + kInletSpeedBound},
       {"maps.end_clearance", "", &O::end_clearance, non_negative(100.0, "m"),
        "Obstacle-free length at each end of the arena, m"},
       {"maps.max_attempts", "", &O::max_attempts, count_range(1, 10'000'000),
        "Draws before giving up on a map"}}};
  return table;
}

namespace {
bool is_building_option(const std::string& name) {
  return name.rfind("maps.building_", 0) == 0;
}
}  // namespace

void RandomMapOptions::validate() const {
  for (const auto& e : random_map_option_table().entries)
    if (!is_building_option(e.name)) validate_entry(e, *this);
  if (!(width > 2 * end_clearance + 0.5))
    throw OptionError(
        "maps.width",
        compact(width) +
            " m leaves no room for obstacles: it must exceed twice maps.end_clearance (" +
            compact(end_clearance) + " m) plus 0.5 m");
  if (!(height > 1.0))
    throw OptionError("maps.height", "must be more than 1 m, got " + compact(height));
  if (families.empty()) {
    std::string thesis;
    for (const std::string& f : thesis_families())
      thesis += (thesis.empty() ? "" : ", ") + f;
    throw OptionError("maps.families",
                      "the list is empty; give one or more families (the "
                      "default is the thesis's " +
                          thesis + ")");
  }
  for (const std::string& f : families)
    check_name("maps.families", f, known_families());
  validate_building();
}

void RandomMapOptions::validate_building() const {
  for (const auto& e : random_map_option_table().entries)
    if (is_building_option(e.name)) validate_entry(e, *this);
  if (building_max_size < building_min_size)
    throw OptionError("maps.building_max_size", compact(building_max_size) +
                                                    " m is less than maps.building_min_size (" +
                                                    compact(building_min_size) + " m)");
}

RandomMap random_map(const RandomMapOptions& o, std::uint64_t seed, std::uint64_t index,
                     std::uint64_t redraw) {
  o.validate();
  Draw d(derive_seed(seed, index, redraw, Stream::MapGeometry));
  RandomMap r;
  r.family = o.families[d.pick(static_cast<int>(o.families.size()))];
  const std::string name = "random-" + std::to_string(seed) + "-" + std::to_string(index) + "-" +
                           (redraw > 0 ? "r" + std::to_string(redraw) + "-" : std::string()) +
                           r.family;
  if (r.family == "building") return random_building(o, d.engine(), name);
  for (r.attempts = 1; r.attempts <= o.max_attempts; ++r.attempts) {
    Map map = default_arena(o.width, o.height);
    map.openings[0].speed = o.inlet_speed;
    // These families fit plumekit-map/1, which keeps the files of datasets
    // made before /2 byte for byte.
    map.format_version = 1;
    map.name = name;
    if (r.family == "two-rectangles" || r.family == "three-rectangles") {
      const int n = r.family == "two-rectangles" ? 2 : 3;
      for (int k = 0; k < n; ++k)
        map.obstacles.push_back(draw_obstacle(d, "rectangle", o));
    } else if (r.family == "shape-and-rectangle") {
      map.obstacles.push_back(draw_obstacle(d, d.pick(2) == 0 ? "l-shape" : "u-shape", o));
      map.obstacles.push_back(draw_obstacle(d, "rectangle", o));
    } else {
      map.obstacles.push_back(draw_obstacle(d, r.family, o));
    }
    if (acceptable(map, o)) {
      r.map = std::move(map);
      return r;
    }
  }
  throw InputError("random maps: no acceptable " + r.family + " map in " +
                   std::to_string(o.max_attempts) +
                   " draws; use a smaller maps.min_gap or maps.robot_margin, or a larger arena");
}

bool FlowCells::fluid_at(Vec2 p) const {
  const int i = std::clamp(static_cast<int>(std::floor(p.x / shape.dx())), 0, shape.nx - 1);
  const int j = std::clamp(static_cast<int>(std::floor(p.y / shape.dy())), 0, shape.ny - 1);
  return !solid[shape.index(i, j)];
}

FlowCells default_flow_cells(const Map& map) {
  const cfd::FlowOptions flow;
  const GridShape shape =
      GridShape::with_cell(map.width, map.height, cfd::resolved_cell(map, flow));
  return {shape, cfd::StaggeredGrid(map, shape, flow).solid_cells()};
}

std::vector<Vec2> random_sources(const Map& map, int count, double clearance, std::uint64_t seed,
                                 std::uint64_t map_index, const FlowCells* flow) {
  std::optional<FlowCells> own;
  if (!flow && count > 0) flow = &own.emplace(default_flow_cells(map));
  Draw d(derive_seed(seed, map_index, 0, Stream::Sources));
  std::vector<Vec2> out;
  int tries = 0;
  while (static_cast<int>(out.size()) < count) {
    if (++tries > 1000 * (count + 1))
      throw InputError("random sources: map " + map.name + " has too little free space at " +
                       compact(clearance) +
                       " m clearance that the flow reaches; use a smaller "
                       "dataset.source_clearance or fewer sources");
    const Vec2 p{d.uniform(clearance, map.width - clearance),
                 d.uniform(clearance, map.height - clearance)};
    if (surrogate::signed_distance(map, p) >= clearance && flow->fluid_at(p)) out.push_back(p);
  }
  return out;
}

}  // namespace plumekit::dataset
