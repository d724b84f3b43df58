// Random maps keep their promises; features follow the contract; SHA-256
// matches the published test vectors.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>

#include "core/error.hpp"
#include "core/seed.hpp"
#include "dataset/random_maps.hpp"
#include "map/map_json.hpp"
#include "map/rasterize.hpp"
#include "surrogate/features.hpp"

namespace plumekit::dataset {
namespace {

TEST(Seed, StreamsDiffer) {
  std::set<std::uint64_t> seen;
  for (std::uint64_t m = 0; m < 20; ++m)
    for (std::uint64_t s = 0; s < 20; ++s)
      for (Stream st : {Stream::MapGeometry, Stream::Sources, Stream::Filaments})
        seen.insert(derive_seed(7, m, s, st));
  EXPECT_EQ(seen.size(), 20u * 20u * 3u);
  EXPECT_EQ(splitmix64(0), 0xe220a8397b1dcdafULL);  // SplitMix64 reference output for seed 0
}

TEST(RandomMaps, AreValidOpenCrossableAndDeterministic) {
  const RandomMapOptions o;
  std::set<std::string> families;
  for (int i = 0; i < 24; ++i) {
    const RandomMap r = random_map(o, 11, i);
    families.insert(r.family);
    const Map& m = r.map;
    EXPECT_NO_THROW(validate_map(m, m.name));
    EXPECT_EQ(m.obstacles.size(), r.family == "two-rectangles" ? 2u : 1u);
    // Inlet and outlet open: no obstacle within end_clearance of them.
    for (const Polygon& p : m.obstacles)
      for (Vec2 v : p) {
        EXPECT_GE(v.x, o.end_clearance - 1e-12);
        EXPECT_LE(v.x, o.width - o.end_clearance + 1e-12);
      }
    EXPECT_TRUE(
        inlet_reaches_outlet(rasterize_labels(m, GridShape::with_cell(m.width, m.height, 0.05))));
    EXPECT_TRUE(robot_can_cross(m, o.robot_margin));
    // Map i is a function of (seed, i) only.
    EXPECT_EQ(map_to_json(random_map(o, 11, i).map), map_to_json(m));
  }
  EXPECT_EQ(families.size(), 4u);
  EXPECT_NE(map_to_json(random_map(o, 12, 0).map), map_to_json(random_map(o, 11, 0).map));
}

TEST(RandomMaps, DefaultFamiliesDrawAsBeforeTheExtraFamiliesExisted) {
  // Pinned from the code before --families: datasets made then stay reproducible.
  const RandomMapOptions o;
  const char* const families[] = {"l-shape",        "u-shape",   "two-rectangles",
                                  "two-rectangles", "rectangle", "l-shape"};
  for (int i = 0; i < 6; ++i)
    EXPECT_EQ(random_map(o, 1, i).family, families[i]) << "map " << i;
  EXPECT_NEAR(random_map(o, 1, 0).map.obstacles[0][0].x, 2.0624712391424884, 1e-12);
}

TEST(RandomMaps, ExtraFamiliesAreOptInAndKeepThePromises) {
  RandomMapOptions o;
  o.families = {"three-rectangles", "shape-and-rectangle"};
  std::set<std::string> families;
  for (int i = 0; i < 16; ++i) {
    const RandomMap r = random_map(o, 3, i);
    families.insert(r.family);
    const Map& m = r.map;
    EXPECT_EQ(family_of(m.name), r.family);
    EXPECT_NO_THROW(validate_map(m, m.name));
    if (r.family == "three-rectangles") {
      ASSERT_EQ(m.obstacles.size(), 3u);
      for (const Polygon& p : m.obstacles)
        EXPECT_EQ(p.size(), 4u);
    } else {
      ASSERT_EQ(m.obstacles.size(), 2u);
      EXPECT_TRUE(m.obstacles[0].size() == 6u || m.obstacles[0].size() == 8u);  // an L or a U
      EXPECT_EQ(m.obstacles[1].size(), 4u);
    }
    EXPECT_TRUE(
        inlet_reaches_outlet(rasterize_labels(m, GridShape::with_cell(m.width, m.height, 0.05))));
    EXPECT_TRUE(robot_can_cross(m, o.robot_margin));
    EXPECT_EQ(map_to_json(random_map(o, 3, i).map), map_to_json(m));
  }
  EXPECT_EQ(families.size(), 2u);
  RandomMapOptions bad;
  bad.families = {"rectangle", "triangle"};
  EXPECT_THROW(random_map(bad, 1, 0), InputError);
  bad.families.clear();
  EXPECT_THROW(random_map(bad, 1, 0), InputError);
}

TEST(RandomMaps, RobotCheckRejectsANarrowGap) {
  Map m = default_arena(10.0, 4.0);
  // A wall across the arena with a 0.2 m slit: air passes, a 0.15 m robot does not.
  m.obstacles = {{{5.0, 0.0}, {5.3, 0.0}, {5.3, 1.9}, {5.0, 1.9}},
                 {{5.0, 2.1}, {5.3, 2.1}, {5.3, 4.0}, {5.0, 4.0}}};
  EXPECT_FALSE(robot_can_cross(m, 0.15));
  EXPECT_TRUE(robot_can_cross(m, 0.05));
}

TEST(RandomSources, StayClearOfObstaclesAndWalls) {
  const RandomMap r = random_map({}, 3, 2);
  const auto s = random_sources(r.map, 200, 0.1, 3, 2);
  ASSERT_EQ(s.size(), 200u);
  for (Vec2 p : s) {
    EXPECT_TRUE(r.map.is_free(p));
    EXPECT_GE(surrogate::signed_distance(r.map, p), 0.1);
  }
}

// Issue 44: a U-shape whose arms reach the top wall seals off the free space inside it; no
// source is drawn there (the flow does not reach it), on the map's default flow grid or another.
TEST(RandomSources, NoneInAPocketTheFlowSealsOff) {
  Map m = default_arena(10.0, 4.0);
  m.obstacles = {{{6.9, 1.4},
                  {8.9, 1.4},
                  {8.9, 4.0},
                  {8.7, 4.0},
                  {8.7, 1.6},
                  {7.1, 1.6},
                  {7.1, 4.0},
                  {6.9, 4.0}}};
  const auto in_pocket = [](Vec2 p) { return p.x > 7.1 && p.x < 8.7 && p.y > 1.6; };
  const FlowCells coarse{GridShape::with_cell(10.0, 4.0, 0.1), {}};
  for (const FlowCells* flow : {static_cast<const FlowCells*>(nullptr), &coarse}) {
    FlowCells cells = flow ? *flow : default_flow_cells(m);
    if (flow) {  // the pocket's cells on a 0.1 m grid, sealed by hand
      cells.solid.assign(cells.shape.size(), 0);
      for (int j = 0; j < cells.shape.ny; ++j)
        for (int i = 0; i < cells.shape.nx; ++i)
          cells.solid[cells.shape.index(i, j)] =
              in_pocket(cells.shape.centre(i, j)) || m.obstacle_at(cells.shape.centre(i, j)) >= 0;
    }
    const auto s = random_sources(m, 300, 0.1, 5, 0, flow ? &cells : nullptr);
    ASSERT_EQ(s.size(), 300u);
    for (Vec2 p : s) {
      EXPECT_FALSE(in_pocket(p)) << to_string(p);
      EXPECT_TRUE(cells.fluid_at(p)) << to_string(p);
    }
  }
}

TEST(Features, FollowTheContract) {
  Map m = default_arena(10.0, 4.0);
  m.obstacles = {{{4.0, 0.0}, {5.0, 0.0}, {5.0, 2.0}, {4.0, 2.0}}};
  const GridShape g = surrogate::feature_grid(m);
  ASSERT_EQ(g.nx, 64);
  ASSERT_EQ(g.ny, 64);
  const std::vector<float> f = surrogate::map_features(m, g);
  ASSERT_EQ(f.size(), 2 * g.size());
  const Grid<std::uint8_t> labels = rasterize_labels(m, g);
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      const std::size_t k = g.index(i, j);
      EXPECT_EQ(f[k], static_cast<float>(labels.values[k]));
      const Vec2 c = g.centre(i, j);
      const float sd = f[g.size() + k];
      if (labels.values[k] == kObstacle) {
        EXPECT_LE(sd, 0.0f);
      } else {
        EXPECT_GT(sd, 0.0f);
      }
      // Exact: the nearest of the obstacle's edges, the floor and the ceiling.
      // Far right of the obstacle: the floor or the ceiling is nearest.
      if (c.x > 7.5) {
        EXPECT_NEAR(sd, std::min(c.y, 4.0 - c.y), 1e-5);
      }
    }
  // Inside the obstacle, 0.25 m from its left edge and deeper from the others.
  EXPECT_NEAR(surrogate::signed_distance(m, {4.25, 1.0}), -0.25, 1e-12);
  const std::vector<float> d = surrogate::source_feature({2.0, 1.0}, g);
  EXPECT_NEAR(d[g.index(10, 20)], std::hypot(g.centre(10, 20).x - 2.0, g.centre(10, 20).y - 1.0),
              1e-5);
}

}  // namespace
}  // namespace plumekit::dataset

namespace plumekit::dataset {
namespace {

TEST(TestMaps, NineValidMapsWithTwentySourcesEach) {
  namespace fs = std::filesystem;
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(fs::path(PLUMEKIT_DATA_DIR) / "test-maps"))
    if (e.path().extension() == ".json") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  ASSERT_EQ(files.size(), 9u);
  for (std::size_t k = 0; k < files.size(); ++k) {
    const Map m = read_map(files[k]);  // validates
    EXPECT_EQ(m.sources.size(), 20u) << files[k];
    EXPECT_EQ(m.obstacles.empty(), k == 0) << files[k] << ": only map 0 is empty";
    EXPECT_TRUE(robot_can_cross(m, 0.15)) << files[k];
    for (Vec2 s : m.sources)
      EXPECT_GE(surrogate::signed_distance(m, s), 0.1) << files[k] << " source " << to_string(s);
  }
}

}  // namespace
}  // namespace plumekit::dataset
