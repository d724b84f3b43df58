// The "building" random-map family: its promises over many seeds (checked
// here independently of the generator's own checks where it is cheap), its
// determinism, its options, and a flow through one.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <vector>

#include "cfd/flow_solver.hpp"
#include "core/error.hpp"
#include "dataset/building_maps.hpp"
#include "dataset/random_maps.hpp"
#include "map/map_json.hpp"
#include "map/rasterize.hpp"
#include "surrogate/features.hpp"

namespace plumekit::dataset {
namespace {

RandomMapOptions buildings() {
  RandomMapOptions o;
  o.families = {"building"};
  return o;
}

// Every coordinate lies on the 0.1 m lattice (so 0.1 m and 0.05 m flow grids
// follow the walls).
bool on_lattice(double v) {
  return std::abs(v * 10.0 - std::round(v * 10.0)) < 1e-9;
}

// Independent of robot_region_connected: the cells (0.1 m) at least `radius`
// from every solid surface by features' signed_distance form one region.
bool eroded_free_space_is_one_region(const Map& map, double radius) {
  const GridShape g = GridShape::with_cell(map.width, map.height, 0.1);
  std::vector<char> ok(g.size()), seen(g.size(), 0);
  long long total = 0;
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i)
      total += ok[g.index(i, j)] = surrogate::signed_distance(map, g.centre(i, j)) >= radius;
  std::vector<std::size_t> stack;
  for (std::size_t k = 0; k < ok.size() && stack.empty(); ++k)
    if (ok[k]) stack.push_back(k), seen[k] = 1;
  long long reached = static_cast<long long>(stack.size());
  while (!stack.empty()) {
    const std::size_t k = stack.back();
    stack.pop_back();
    const int i = static_cast<int>(k % g.nx), j = static_cast<int>(k / g.nx);
    for (auto [a, b] : {std::pair{i + 1, j}, {i - 1, j}, {i, j + 1}, {i, j - 1}}) {
      if (!g.contains(a, b) || !ok[g.index(a, b)] || seen[g.index(a, b)]) continue;
      seen[g.index(a, b)] = 1;
      ++reached;
      stack.push_back(g.index(a, b));
    }
  }
  return total > 0 && reached == total;
}

// Cells labelled inlet (outlet) on the 5 cm grid: one per 5 cm of every inlet
// (outlet), i.e. no opening is blocked by furniture or a wall.
void expect_openings_labelled(const Map& map) {
  const Grid<std::uint8_t> labels =
      rasterize_labels(map, GridShape::with_cell(map.width, map.height, 0.05));
  long long want[2] = {0, 0}, got[2] = {0, 0};
  for (const Opening& o : map.openings)
    want[o.is_inlet() ? 0 : 1] += std::lround(o.length() / 0.05);
  for (auto v : labels.values) {
    got[0] += v == kInlet;
    got[1] += v == kOutlet;
  }
  EXPECT_EQ(got[0], want[0]) << map.name;
  EXPECT_EQ(got[1], want[1]) << map.name;
}

void expect_promises_kept(const RandomMap& r, const RandomMapOptions& o) {
  const Map& m = r.map;
  EXPECT_EQ(r.family, "building");
  EXPECT_EQ(family_of(m.name), "building");
  EXPECT_EQ(m.format_version, 2);
  EXPECT_NO_THROW(validate_map(m, m.name));
  EXPECT_GE(m.width, o.building_min_size);
  EXPECT_LE(m.width, o.building_max_size);
  EXPECT_GE(m.height, o.building_min_size);
  EXPECT_LE(m.height, o.building_max_size);
  EXPECT_TRUE(on_lattice(m.width) && on_lattice(m.height)) << m.name;
  for (const Polygon& p : m.obstacles)
    for (Vec2 v : p)
      EXPECT_TRUE(on_lattice(v.x) && on_lattice(v.y)) << m.name;
  EXPECT_TRUE(openings_open(m, 0.05)) << m.name;
  expect_openings_labelled(m);
  EXPECT_TRUE(free_space_connected(m, 0.05)) << m.name;
  EXPECT_TRUE(
      inlet_reaches_outlet(rasterize_labels(m, GridShape::with_cell(m.width, m.height, 0.05))))
      << m.name;
  EXPECT_EQ(building_fault(m, o), "") << m.name;
}

// A 0.8 m door leaves 0.4 m each side of its middle; 0.1 m cells see at least
// 0.35 m of it. (Slow: signed_distance visits every obstacle per cell.)
void expect_robot_passes(const Map& m, const RandomMapOptions& o) {
  EXPECT_TRUE(eroded_free_space_is_one_region(m, 0.5 * o.building_passage - 0.05 - 1e-9)) << m.name;
}

TEST(BuildingMaps, KeepTheirPromisesOverManySeeds) {
  const RandomMapOptions o = buildings();
  std::set<std::size_t> opening_counts;
  int windows = 0, doors = 0, furnished = 0;
  for (std::uint64_t k = 0; k < 50; ++k) {
    const RandomMap r = random_map(o, 1 + k / 10, k % 10);
    expect_promises_kept(r, o);
    if (k % 5 == 0) expect_robot_passes(r.map, o);
    opening_counts.insert(r.map.openings.size());
    for (const Opening& op : r.map.openings)
      (r.map.wall_of(op) ? doors : windows) += 1;
    furnished += r.map.obstacles.size() > 12;
  }
  // The family varies: several openings, doors and windows, furniture.
  EXPECT_GE(opening_counts.size(), 3u);
  EXPECT_GT(windows, 10);
  EXPECT_GT(doors, 10);
  EXPECT_GT(furnished, 25);
}

TEST(BuildingMaps, SameSeedSameBytesOtherSeedsOtherMaps) {
  const RandomMapOptions o = buildings();
  std::set<std::string> texts;
  for (std::uint64_t seed : {1, 2})
    for (std::uint64_t index : {0, 1, 2}) {
      const std::string a = map_file_text(random_map(o, seed, index).map, "a");
      EXPECT_EQ(a, map_file_text(random_map(o, seed, index).map, "b"));
      texts.insert(a);
    }
  EXPECT_EQ(texts.size(), 6u);
  // A redraw is another map.
  EXPECT_NE(map_file_text(random_map(o, 1, 0, 1).map, "a"), *texts.begin());
}

TEST(BuildingMaps, SizesFollowTheOptions) {
  RandomMapOptions o = buildings();
  o.building_min_size = o.building_max_size = 8.0;
  for (std::uint64_t k = 0; k < 10; ++k) {
    const RandomMap r = random_map(o, 3, k);
    EXPECT_EQ(r.map.width, 8.0);
    EXPECT_EQ(r.map.height, 8.0);
    expect_promises_kept(r, o);
    expect_robot_passes(r.map, o);
  }
  o.building_min_size = 6.0;
  o.building_max_size = 6.5;
  o.building_passage = 1.2;
  for (std::uint64_t k = 0; k < 10; ++k) {
    const RandomMap r = random_map(o, 4, k);
    expect_promises_kept(r, o);
    expect_robot_passes(r.map, o);
  }
}

void expect_refused(const RandomMapOptions& o, const std::string& field) {
  try {
    o.validate();
    FAIL() << "accepted " << field;
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), field);
  }
}

TEST(BuildingMaps, RefusesBadOptionsNamingTheField) {
  RandomMapOptions o = buildings();
  o.building_min_size = 3.0;
  expect_refused(o, "maps.building_min_size");
  o = buildings();
  o.building_max_size = 200.0;
  expect_refused(o, "maps.building_max_size");
  o = buildings();
  o.building_min_size = 12.0;
  o.building_max_size = 10.0;
  expect_refused(o, "maps.building_max_size");
  o = buildings();
  o.building_passage = 0.1;
  expect_refused(o, "maps.building_passage");
  o.building_passage = std::nan("");
  expect_refused(o, "maps.building_passage");
}

TEST(BuildingMaps, TheChecksSeeABlockedOpeningAndASealedRoom) {
  const RandomMapOptions o = buildings();
  RandomMap r = random_map(o, 5, 0);
  Map blocked = r.map;
  // A box against the first opening's free side.
  const Opening& op = blocked.first_inlet();
  const Vec2 n = blocked.inward_normal(op);
  const Vec2 a = op.from, b = op.to + 0.3 * n;
  blocked.obstacles.push_back({{std::min(a.x, b.x), std::min(a.y, b.y)},
                               {std::max(a.x, b.x), std::min(a.y, b.y)},
                               {std::max(a.x, b.x), std::max(a.y, b.y)},
                               {std::min(a.x, b.x), std::max(a.y, b.y)}});
  EXPECT_FALSE(openings_open(blocked, 0.05));
  EXPECT_NE(building_fault(blocked, o), "");
  // A closed box of walls in free space is a sealed room.
  Map sealed = r.map;
  const double w = sealed.width, h = sealed.height;
  const double x0 = 0.4 * w, x1 = 0.6 * w, y0 = 0.4 * h, y1 = 0.6 * h;
  sealed.obstacles = {{{x0, y0}, {x1, y0}, {x1, y0 + 0.1}, {x0, y0 + 0.1}},
                      {{x0, y1 - 0.1}, {x1, y1 - 0.1}, {x1, y1}, {x0, y1}},
                      {{x0, y0 + 0.1}, {x0 + 0.1, y0 + 0.1}, {x0 + 0.1, y1 - 0.1}, {x0, y1 - 0.1}},
                      {{x1 - 0.1, y0 + 0.1}, {x1, y0 + 0.1}, {x1, y1 - 0.1}, {x1 - 0.1, y1 - 0.1}}};
  EXPECT_TRUE(free_space_connected(r.map, 0.05));
  EXPECT_FALSE(free_space_connected(sealed, 0.05));
  // A 0.6 m gap between two walls is too narrow for the 0.8 m passage.
  Map narrow;
  narrow.width = 6.0;
  narrow.height = 4.0;
  narrow.obstacles = {{{3.0, 0.0}, {3.1, 0.0}, {3.1, 1.7}, {3.0, 1.7}},
                      {{3.0, 2.3}, {3.1, 2.3}, {3.1, 4.0}, {3.0, 4.0}}};
  EXPECT_TRUE(robot_region_connected(narrow, 0.25, 0.05));
  EXPECT_FALSE(robot_region_connected(narrow, 0.35, 0.05));
}

TEST(BuildingMaps, ASmallBuildingSolvesAFlowThatBalancesMass) {
  RandomMapOptions o = buildings();
  o.building_min_size = 6.0;
  o.building_max_size = 8.0;
  const Map map = random_map(o, 1, 0).map;
  cfd::FlowOptions f;
  f.cell = 0.1;
  // As the dataset generator falls back to when central differences stall.
  f.convection = cfd::Convection::Upwind;
  const cfd::FlowResult r = cfd::solve(map, f);
  EXPECT_TRUE(r.summary.converged);
  double inflow = 0.0;
  for (const Opening& op : map.openings)
    if (op.is_inlet()) inflow += op.speed * op.length();
  EXPECT_NEAR(r.summary.inflow, inflow, 1e-9 * inflow);
  EXPECT_NEAR(r.summary.outflow, inflow, 1e-9 * inflow);
  EXPECT_LT(r.summary.mass_imbalance, 1e-10);
}

namespace fs = std::filesystem;

int run(const std::string& cmd) {
  const int rc = std::system(cmd.c_str());
  return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

TEST(BuildingMapsCli, MapsRandomWritesMap2FilesThatADatasetAccepts) {
  const fs::path dir = fs::temp_directory_path() / "plumekit-building-cli";
  fs::remove_all(dir);
  const std::string exe = PLUMEKIT_EXE;
  const std::string maps = (dir / "maps").string(), data = (dir / "data").string();
  ASSERT_EQ(run(exe + " maps random --families building --count 2 --sources 1 --seed 7 " +
                "--building-min-size 6 --building-max-size 7 --out " + maps + " > /dev/null"),
            0);
  for (const char* f : {"map-00000.json", "map-00001.json"}) {
    const fs::path file = fs::path(maps) / f;
    std::ifstream in(file);
    std::string first_lines((std::istreambuf_iterator<char>(in)), {});
    EXPECT_NE(first_lines.find("\"plumekit-map/2\""), std::string::npos) << f;
    const Map m = read_map(file);
    EXPECT_EQ(family_of(m.name), "building");
    EXPECT_LE(m.width, 7.0);
    EXPECT_EQ(m.sources.size(), 1u);
  }
  // The same maps from the library: the CLI only binds the fields.
  RandomMapOptions o = buildings();
  o.building_min_size = 6.0;
  o.building_max_size = 7.0;
  EXPECT_EQ(read_map(fs::path(maps) / "map-00001.json").obstacles,
            random_map(o, 7, 1).map.obstacles);
  // A coarse dataset over them.
  ASSERT_EQ(run(exe + " dataset generate --map-dir " + maps + " --cell 0.2 --threads 1 --out " +
                data + " > /dev/null 2>&1"),
            0);
  EXPECT_TRUE(fs::exists(fs::path(data) / "manifest.json"));
  // A bad field is refused before anything is written.
  const std::string bad = (dir / "bad").string();
  EXPECT_EQ(run(exe + " maps random --families building --building-passage 0.1 --out " + bad +
                " 2> /dev/null"),
            2);
  EXPECT_FALSE(fs::exists(bad));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace plumekit::dataset
