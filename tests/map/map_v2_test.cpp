// plumekit-map/2: openings anywhere on the free space's boundary, the frame,
// writing and reading back, every refusal, and /1 files kept as /1.
#include <gtest/gtest.h>

#include <filesystem>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "map/map_json.hpp"
#include "map/rasterize.hpp"
#include "support/map_errors.hpp"

namespace plumekit {
namespace {

namespace fs = std::filesystem;
const fs::path kData = fs::path(PLUMEKIT_DATA_DIR);
const fs::path kBuilding = fs::path(PLUMEKIT_TEST_DATA) / "maps-v2" / "building.json";

// A /2 map of a 6 x 4 m arena framed at (10, 20), with `openings` and an
// outer-wall band along the top (y 3.6..4 in the arena, 23.6..24 in the frame).
std::string v2_text(const std::string& openings, const std::string& extra = "") {
  return R"({"format": "plumekit-map/2", "name": "t", "frame": {"origin": [10, 20]},
             "size": [6, 4], "openings": [)" +
         openings + R"(], "obstacles": [[[10, 23.6], [16, 23.6], [16, 24], [10, 24]]])" + extra +
         "}";
}
const std::string kInletJson = R"({"kind": "inlet", "from": [10, 21], "to": [10, 22], "speed": 1})";
const std::string kOutletJson = R"({"kind": "outlet", "from": [12, 23.6], "to": [13, 23.6]})";

using test::expect_map_rejected;
using test::map_error_of;

TEST(MapV2, ReadsOpeningsAndFrameIntoArenaCoordinates) {
  const Map map =
      parse_map(v2_text(kInletJson + ", " + kOutletJson, R"(, "sources": [[11, 21.5]])"), "x");
  EXPECT_EQ(map.format_version, 2);
  EXPECT_EQ(map.frame.origin, (Vec2{10, 20}));
  ASSERT_EQ(map.openings.size(), 2u);
  const Opening& in = map.openings[0];
  EXPECT_TRUE(in.is_inlet());
  EXPECT_EQ(in.from, (Vec2{0, 1}));
  EXPECT_EQ(in.to, (Vec2{0, 2}));
  EXPECT_EQ(map.wall_of(in), Side::Left);
  EXPECT_EQ(map.inward_normal(in), (Vec2{1, 0}));
  const Opening& out = map.openings[1];
  EXPECT_FALSE(out.is_inlet());
  EXPECT_FALSE(map.wall_of(out).has_value());  // on the band's lower edge
  EXPECT_DOUBLE_EQ(out.line(), 3.6);
  EXPECT_EQ(map.inward_normal(out), (Vec2{0, -1}));  // the free side is below the band
  EXPECT_EQ(map.sources[0], (Vec2{1, 1.5}));
  EXPECT_NEAR(map.obstacles[0][0].y, 3.6, 1e-12);  // 23.6 - 20 in doubles
  EXPECT_EQ(map.to_frame(map.sources[0]), (Vec2{11, 21.5}));
}

TEST(MapV2, FrameRoundTripGivesTheSameTextAndMap) {
  const Map map = read_map(kBuilding);
  const std::string text = map_file_text(map, "x");
  const Map again = parse_map(text, "x");
  EXPECT_EQ(map_file_text(again, "x"), text);
  EXPECT_EQ(map_to_json(again), map_to_json(map));
  // Map-frame values come back as written (-2.0 + 3.6 - ... is not exact in doubles).
  EXPECT_NE(text.find("[1.0,1.6]"), std::string::npos) << text;
  EXPECT_NE(text.find("\"frame\": {\"origin\":[-3.0,-2.0]}"), std::string::npos) << text;
  EXPECT_EQ(again.openings.size(), 4u);
  for (std::size_t k = 0; k < map.openings.size(); ++k) {
    EXPECT_NEAR(again.openings[k].from.x, map.openings[k].from.x, 1e-12);
    EXPECT_NEAR(again.openings[k].to.y, map.openings[k].to.y, 1e-12);
  }
}

TEST(MapV2, VersionOneFilesAreWrittenBackAsVersionOne) {
  int n = 0;
  for (const fs::path& dir : {kData / "maps", kData / "test-maps"})
    for (const auto& entry : fs::directory_iterator(dir)) {
      const Map map = read_map(entry.path());
      EXPECT_EQ(map.format_version, 1) << entry.path();
      // The same content as the file (its spacing is the hand-laid one),
      // in the /1 keys, and the writer's own text is a fixed point.
      const std::string text = map_file_text(map, "x");
      EXPECT_EQ(nlohmann::ordered_json::parse(text),
                nlohmann::ordered_json::parse(read_file(entry.path())))
          << entry.path();
      EXPECT_EQ(map_file_text(parse_map(text, "x"), "x"), text);
      ++n;
    }
  EXPECT_GE(n, 13);
}

TEST(MapV2, AMapThatOutgrowsVersionOneIsNotWrittenAsVersionOne) {
  Map map = read_map(kData / "maps" / "empty.json");
  map.openings.push_back(wall_opening(map, Side::Top, 1, 2, OpeningKind::Outlet));
  try {
    map_file_text(map, "out.json");
    FAIL() << "a /1 map with three openings was written";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("write this map as plumekit-map/2"), std::string::npos);
  }
  map.format_version = 2;
  EXPECT_EQ(parse_map(map_file_text(map, "x"), "x").openings.size(), 3u);
}

TEST(MapV2, RefusesBadOpenings) {
  expect_map_rejected(v2_text(kInletJson), "openings", "no outlet");
  expect_map_rejected(v2_text(kOutletJson), "openings", "no inlet");
  expect_map_rejected(
      v2_text(R"({"kind": "vent", "from": [10, 21], "to": [10, 22]}, )" + kOutletJson),
      "openings[0].kind", "not an opening");
  expect_map_rejected(
      v2_text(R"({"kind": "inlet", "from": [10, 21], "to": [10, 22]}, )" + kOutletJson),
      "openings[0].speed", "missing");
  expect_map_rejected(
      v2_text(R"({"kind": "inlet", "from": [10, 21], "to": [10, 22], "speed": 0}, )" + kOutletJson),
      "openings[0].speed", "positive");
  // Faster than an incompressible flow holds (well below Mach 0.3).
  for (const char* fast : {"1e6", "100.5"})
    expect_map_rejected(v2_text(R"({"kind": "inlet", "from": [10, 21], "to": [10, 22], "speed": )" +
                                std::string(fast) + "}, " + kOutletJson),
                        "openings[0].speed", "too fast; an inlet blows at most 100 m/s");
  EXPECT_EQ(map_error_of(v2_text(R"({"kind": "inlet", "from": [10, 21], "to": [10, 22],
                                     "speed": 100}, )" +
                                 kOutletJson)),
            "");
  expect_map_rejected(
      v2_text(kInletJson + R"(, {"kind": "outlet", "from": [12, 23.6], "to": [13, 23.6],
                                        "speed": 1})"),
      "openings[1].speed", "unknown key");
  expect_map_rejected(
      v2_text(kInletJson + R"(, {"kind": "outlet", "from": [12, 23.6], "to": [13, 23]})"),
      "openings[1]", "not parallel to an axis");
  expect_map_rejected(
      v2_text(kInletJson + R"(, {"kind": "outlet", "from": [12, 23.6], "to": [12, 23.6]})"),
      "openings[1]", "same point");
  expect_map_rejected(
      v2_text(kInletJson + R"(, {"kind": "outlet", "from": [15, 23.6], "to": [17, 23.6]})"),
      "openings[1]", "outside the arena");
  // In the open, inside the band, and with free space on one side then the other.
  expect_map_rejected(
      v2_text(kInletJson + R"(, {"kind": "outlet", "from": [12, 22], "to": [13, 22]})"),
      "openings[1]", "crosses free space");
  expect_map_rejected(
      v2_text(kInletJson + R"(, {"kind": "outlet", "from": [12, 23.8], "to": [13, 23.8]})"),
      "openings[1]", "inside an obstacle");
  expect_map_rejected(
      R"({"format": "plumekit-map/2", "name": "t", "size": [6, 4], "openings": [)" +
          std::string(R"({"kind": "inlet", "from": [0, 1], "to": [0, 2], "speed": 1},
                                  {"kind": "outlet", "from": [2, 1], "to": [4, 1]}],
                      "obstacles": [[[1, 0], [3, 0], [3, 1], [1, 1]],
                                    [[3, 1], [5, 1], [5, 2], [3, 2]]]})"),
      "openings[1]", "free side changes");
}

TEST(MapV2, RefusesOverlapsButAllowsOpeningsEndToEnd) {
  const std::string second_outlet = R"({"kind": "outlet", "from": [12.5, 23.6], "to": [14, 23.6]})";
  expect_map_rejected(v2_text(kInletJson + ", " + kOutletJson + ", " + second_outlet),
                      "openings[2]", "overlaps openings[1]");
  expect_map_rejected(
      v2_text(kInletJson + ", " + kOutletJson +
              R"(, {"kind": "inlet", "from": [12.5, 23.6], "to": [14, 23.6], "speed": 1})"),
      "openings[2]", "an inlet and an outlet cannot share a stretch");
  EXPECT_EQ(map_error_of(v2_text(kInletJson + ", " + kOutletJson +
                                 R"(, {"kind": "outlet", "from": [13, 23.6], "to": [14, 23.6]})")),
            "");
}

TEST(MapV2, RefusesBadFramesAndUnknownKeys) {
  expect_map_rejected(R"({"format": "plumekit-map/2", "size": [6, 4], "frame": {"origin": [1]},
                      "openings": []})",
                      "frame.origin", "expected a point");
  expect_map_rejected(R"({"format": "plumekit-map/2", "size": [6, 4], "frame": {"origin": [0, 0],
                      "yaw": 0.1}, "openings": []})",
                      "frame.yaw", "unknown key");
  expect_map_rejected(R"({"format": "plumekit-map/2", "size": [6, 4], "frame": {"origin": [1e8, 0]},
                      "openings": []})",
                      "frame.origin", "within 1e7 m");
  expect_map_rejected(R"({"format": "plumekit-map/2", "size": [6, 4], "inlet": {"side": "left"}})",
                      "inlet", "unknown key");
  expect_map_rejected(R"({"format": "plumekit-map/2", "size": [6, 4]})", "openings", "missing");
}

// Robot starts, for evaluate: map-frame points in free space, written back
// only when a map has them (so a map without keeps its bytes).
TEST(MapV2, StartsAreReadInTheFrameAndWrittenBackOnlyWhenPresent) {
  const std::string openings = kInletJson + ", " + kOutletJson;
  const Map map = parse_map(
      v2_text(openings, R"(, "sources": [[11, 21.5]], "starts": [[15, 22], [12.5, 20.5]])"), "x");
  ASSERT_EQ(map.starts.size(), 2u);
  EXPECT_EQ(map.starts[0], (Vec2{5, 2}));
  EXPECT_EQ(map.to_frame(map.starts[1]), (Vec2{12.5, 20.5}));
  const std::string text = map_file_text(map, "x");
  EXPECT_NE(text.find("\"starts\": [\n    [15.0,22.0],\n    [12.5,20.5]\n  ]\n}"),
            std::string::npos)
      << text;
  EXPECT_EQ(parse_map(text, "x").starts, map.starts);
  EXPECT_EQ(map_file_text(read_map(kBuilding), "x").find("starts"), std::string::npos);

  expect_map_rejected(v2_text(openings, R"(, "starts": [[12, 23.8]])"), "starts[0]",
                      "lies inside obstacles[0]");
  expect_map_rejected(v2_text(openings, R"(, "starts": [[12, 30]])"), "starts[0]",
                      "outside the arena");
  expect_map_rejected(v2_text(openings, R"(, "starts": [[12, 21], [1]])"), "starts[1]",
                      "expected a point");
  expect_map_rejected(
      R"({"format": "plumekit-map/1", "size": [10, 4], "inlet": {"side": "left"},
          "outlet": {"side": "right"}, "starts": [[1, 1]]})",
      "starts", "unknown key");
}

TEST(MapV2, OpeningsOnObstacleEdgesLabelTheCellsBesideThem) {
  const Map map = read_map(kBuilding);
  const GridShape s = GridShape::with_cell(map.width, map.height, 0.1);
  const Grid<std::uint8_t> l = rasterize_labels(map, s);
  // The outlet on the band's lower edge (x 4..5, y 3.6): the row below it.
  EXPECT_EQ(l(44, 35), kOutlet);
  EXPECT_EQ(l(44, 36), kObstacle);
  EXPECT_EQ(l(44, 34), kFree);
  EXPECT_EQ(l(35, 35), kFree);  // the band's edge outside the outlet is plain obstacle side
  // The inlets on the left wall (y 0.5..1.5) and the bottom wall (x 2..3), the outlet on the right.
  EXPECT_EQ(l(0, 10), kInlet);
  EXPECT_EQ(l(0, 20), kWall);
  EXPECT_EQ(l(25, 0), kInlet);
  EXPECT_EQ(l(59, 15), kOutlet);
  EXPECT_TRUE(inlet_reaches_outlet(l));
}

}  // namespace
}  // namespace plumekit
