#include "map/map_json.hpp"
#include "support/map_errors.hpp"

#include <gtest/gtest.h>

#include <filesystem>

#include "core/error.hpp"

namespace plumekit {
namespace {

const std::filesystem::path kMaps = std::filesystem::path(PLUMEKIT_DATA_DIR) / "maps";

// A valid map with `patch` spliced in place of the obstacles/sources lines.
std::string map_text(const std::string& body) {
  return R"({"format": "plumekit-map/1", "name": "t", )" + body + "}";
}
const std::string kHead =
    R"("size": [10, 4], "inlet": {"side": "left", "speed": 1.0}, "outlet": {"side": "right"})";

using test::expect_map_rejected;
using test::map_error_of;

TEST(MapJson, ShippedMapsAreValid) {
  int n = 0;
  for (const auto& entry : std::filesystem::directory_iterator(kMaps)) {
    const Map map = read_map(entry.path());
    EXPECT_DOUBLE_EQ(map.width, 10.0) << entry.path();
    EXPECT_DOUBLE_EQ(map.height, 4.0) << entry.path();
    ++n;
  }
  EXPECT_GE(n, 3);
}

TEST(MapJson, DefaultsAndFields) {
  const Map map = parse_map(map_text(kHead + R"(, "obstacles": [[[2,0],[3,0],[3,2]]],
                                                   "sources": [[1, 1]])"),
                            "x");
  ASSERT_EQ(map.openings.size(), 2u);
  EXPECT_EQ(map.format_version, 1);
  EXPECT_EQ(map.wall_of(map.openings[0]), Side::Left);
  EXPECT_DOUBLE_EQ(map.openings[0].lo(), 0.0);
  EXPECT_DOUBLE_EQ(map.openings[0].hi(), 4.0);  // whole wall by default
  EXPECT_EQ(map.openings[0].profile, Profile::Uniform);
  EXPECT_EQ(map.wall_of(map.openings[1]), Side::Right);
  EXPECT_DOUBLE_EQ(map.openings[1].hi(), 4.0);
  ASSERT_EQ(map.obstacles.size(), 1u);
  EXPECT_EQ(map.obstacles[0].size(), 3u);
  ASSERT_EQ(map.sources.size(), 1u);
  EXPECT_EQ(map.sources[0], (Vec2{1, 1}));
}

TEST(MapJson, WriteThenReadGivesTheSameMap) {
  const Map a = read_map(kMaps / "cluttered-3.json");
  const auto path = std::filesystem::temp_directory_path() / "plumekit_roundtrip.json";
  write_map(a, path);
  const Map b = read_map(path);
  std::filesystem::remove(path);
  EXPECT_EQ(map_to_json(a), map_to_json(b));
  EXPECT_EQ(b.obstacles.size(), 3u);
}

TEST(MapJson, RejectsSelfIntersectingPolygon) {
  expect_map_rejected(map_text(kHead + R"(, "obstacles": [[[2,1],[4,3],[4,1],[2,3]]])"),
                      "obstacles[0]", "not simple");
}

TEST(MapJson, RejectsPolygonOutsideArena) {
  expect_map_rejected(map_text(kHead + R"(, "obstacles": [[[9,1],[10.5,1],[10.5,2],[9,2]]])"),
                      "obstacles[0][1]", "outside");
}

TEST(MapJson, RejectsPolygonWithTwoVertices) {
  expect_map_rejected(map_text(kHead + R"(, "obstacles": [[[2,1],[3,1]]])"), "obstacles[0]",
                      "at least 3");
}

TEST(MapJson, RejectsUnknownKeys) {
  expect_map_rejected(map_text(kHead + R"(, "obstacle": [])"), "obstacle", "unknown key");
  expect_map_rejected(map_text(R"("size": [10, 4], "inlet": {"side": "left", "sped": 1},
                              "outlet": {"side": "right"})"),
                      "inlet.sped", "unknown key");
}

TEST(MapJson, RejectsMissingSize) {
  expect_map_rejected(
      map_text(R"("inlet": {"side": "left", "speed": 1}, "outlet": {"side": "right"})"), "size",
      "missing");
}

TEST(MapJson, RejectsNaNAndInfinity) {
  // Bare NaN, as Python's json.dump writes it.
  expect_map_rejected(map_text(kHead + R"(, "obstacles": [[[2,0],[3,NaN],[3,2]]])"),
                      "obstacles[0][1][1]", "NaN");
  expect_map_rejected(map_text(kHead + R"(, "sources": [[-Infinity, 1]])"), "sources[0][0]",
                      "Infinity");
  // Too large for a double: the parser names the number, not the key.
  expect_map_rejected(map_text(kHead + R"(, "sources": [[1e999, 1]])"), "1e999", "overflow");
  // NaN inside a string is just text.
  const Map named = parse_map(
      R"({"format": "plumekit-map/1", "name": "NaN \"Infinity\" room", )" + kHead + "}", "x");
  EXPECT_EQ(named.name, "NaN \"Infinity\" room");
}

TEST(MapJson, RejectsSourceInsideObstacleOrOutsideArena) {
  expect_map_rejected(map_text(kHead + R"(, "obstacles": [[[2,0],[3,0],[3,2],[2,2]]],
                                         "sources": [[0.5, 0.5], [2.5, 1]])"),
                      "sources[1]", "inside obstacles[0]");
  expect_map_rejected(map_text(kHead + R"(, "obstacles": [[[2,0],[3,0],[3,2],[2,2]]],
                                         "sources": [[3, 1]])"),
                      "sources[0]", "inside obstacles[0]");  // on the boundary counts as inside
  expect_map_rejected(map_text(kHead + R"(, "sources": [[11, 1]])"), "sources[0]",
                      "outside the arena");
}

TEST(MapJson, RejectsImpossibleOrOverlappingSpans) {
  expect_map_rejected(map_text(R"("size": [10, 4], "inlet": {"side": "left", "from": 3, "to": 1,
                              "speed": 1}, "outlet": {"side": "right"})"),
                      "inlet", "empty");
  expect_map_rejected(map_text(R"("size": [10, 4], "inlet": {"side": "left", "to": 5, "speed": 1},
                              "outlet": {"side": "right"})"),
                      "inlet", "outside the wall");
  expect_map_rejected(map_text(R"("size": [10, 4], "inlet": {"side": "left", "to": 2.5, "speed": 1},
                              "outlet": {"side": "left", "from": 2})"),
                      "outlet", "overlaps");
  expect_map_rejected(map_text(R"("size": [10, 4], "inlet": {"side": "west", "speed": 1},
                              "outlet": {"side": "right"})"),
                      "inlet.side", "not a side");
  expect_map_rejected(map_text(R"("size": [10, 4], "inlet": {"side": "left", "speed": -1},
                              "outlet": {"side": "right"})"),
                      "inlet.speed", "positive");
  expect_map_rejected(map_text(R"("size": [10, 4], "inlet": {"side": "left", "speed": 1e6},
                                  "outlet": {"side": "right"})"),
                      "inlet.speed", "1e+06 m/s is too fast; an inlet blows at most 100 m/s");
  // Inlet and outlet may share a wall when their spans only touch.
  EXPECT_EQ(
      map_error_of(map_text(R"("size": [10, 4], "inlet": {"side": "left", "to": 2, "speed": 1},
                                 "outlet": {"side": "left", "from": 2})")),
      "");
}

TEST(MapJson, RejectsBadSyntaxTypesAndVersions) {
  expect_map_rejected("{\n  \"format\": \"plumekit-map/1\",\n  \"size\": [10 4]\n}", "", "line 3");
  expect_map_rejected(map_text(R"("size": [10, "4"], "inlet": {"side": "left", "speed": 1},
                              "outlet": {"side": "right"})"),
                      "size[1]", "expected a number");
  expect_map_rejected(R"({"format": "plumekit-map/3"})", "format", "not supported");
  expect_map_rejected(map_text(kHead + R"(, "sources": [], "sources": [])"), "sources", "twice");
  expect_map_rejected(map_text(R"("size": [0, 4], "inlet": {"side": "left", "speed": 1},
                              "outlet": {"side": "right"})"),
                      "size", "positive");
}

TEST(MapJson, MissingFileIsAnInputError) {
  EXPECT_THROW(read_map("/nonexistent/map.json"), InputError);
}

}  // namespace
}  // namespace plumekit
