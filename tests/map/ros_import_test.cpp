#include "map/ros_import.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "core/error.hpp"
#include "map/connectivity.hpp"
#include "map/map_json.hpp"
#include "map/occupancy_cleanup.hpp"
#include "map/opening_snap.hpp"
#include "map/rasterize.hpp"

namespace plumekit {
namespace {

namespace fs = std::filesystem;

// A cluttered room as map_saver would write it: 254 free, 0 occupied, 205 unknown.
// Outside the room is unknown; the room has 2-pixel walls, a door gap, furniture,
// a round table, a diagonal cabinet, a one-pixel pole and a diagonal pinch.
cv::Mat cluttered_room() {
  cv::Mat img(120, 200, CV_8U, cv::Scalar(205));
  cv::rectangle(img, cv::Rect(10, 10, 180, 100), cv::Scalar(254), cv::FILLED);
  cv::rectangle(img, cv::Rect(10, 10, 180, 100), cv::Scalar(0), 2);
  cv::rectangle(img, cv::Rect(9, 50, 3, 16), cv::Scalar(254), cv::FILLED);  // door in the left wall
  cv::rectangle(img, cv::Rect(40, 30, 30, 12), cv::Scalar(0), cv::FILLED);  // desk
  cv::rectangle(img, cv::Rect(40, 42, 8, 30), cv::Scalar(0), cv::FILLED);   // L-shaped return
  cv::circle(img, cv::Point(120, 70), 14, cv::Scalar(0), cv::FILLED);       // round table
  const std::vector<cv::Point> cabinet{{150, 20}, {175, 45}, {168, 52}, {143, 27}};
  cv::fillConvexPoly(img, cabinet, cv::Scalar(0));
  img.at<uchar>(90, 90) = 0;  // a pole, one pixel
  img.at<uchar>(95, 60) = 0;  // two pixels touching only at a corner
  img.at<uchar>(96, 61) = 0;
  // A closet: a small room inside the room, with its own content.
  cv::rectangle(img, cv::Rect(85, 20, 20, 20), cv::Scalar(0), 2);
  cv::rectangle(img, cv::Rect(93, 28, 4, 4), cv::Scalar(0), cv::FILLED);
  return img;
}

struct TempDir {
  fs::path path = fs::temp_directory_path() / ("plumekit_ros_" + std::to_string(::getpid()));
  TempDir() { fs::create_directories(path); }
  ~TempDir() { fs::remove_all(path); }
};

fs::path write_ros_map(const fs::path& dir, const cv::Mat& img, const std::string& extra = "") {
  cv::imwrite((dir / "room.pgm").string(), img);
  std::ofstream(dir / "room.yaml") << "image: room.pgm\nresolution: 0.05\n"
                                      "origin: [-2.0, -1.5, 0.0]\nnegate: 0\n"
                                      "occupied_thresh: 0.65\nfree_thresh: 0.196\n"
                                   << extra;
  return dir / "room.yaml";
}

// Occupancy of `map` at the image's resolution, in image row order.
cv::Mat rasterize_like_image(const Map& map, int cols, int rows) {
  const auto g = rasterize_occupancy(map, GridShape{cols, rows, map.width, map.height});
  cv::Mat out(rows, cols, CV_8U);
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c)
      out.at<uchar>(r, c) = g(c, rows - 1 - r);
  return out;
}

TEST(RosImport, ClutteredRoomRoundTripsWithinOneCellAtTheBoundary) {
  TempDir tmp;
  const fs::path yaml = write_ros_map(tmp.path, cluttered_room());
  const RosImport in = import_ros_map(yaml, {});
  EXPECT_DOUBLE_EQ(in.map.width, 10.0);
  EXPECT_DOUBLE_EQ(in.map.height, 6.0);
  EXPECT_DOUBLE_EQ(in.ros_origin.x, -2.0);
  EXPECT_GT(in.stats.cuts, 0);            // the room encloses free space
  EXPECT_GT(in.stats.pinches_filled, 0);  // the diagonal pair
  EXPECT_NO_THROW(validate_map(in.map, "imported"));

  const cv::Mat back = rasterize_like_image(in.map, in.cols, in.rows);
  cv::Mat dilated, eroded;
  const cv::Mat kernel = cv::Mat::ones(3, 3, CV_8U);
  cv::dilate(in.occupied, dilated, kernel);
  cv::erode(in.occupied, eroded, kernel);
  int mismatched = 0;
  for (int r = 0; r < in.rows; ++r)
    for (int c = 0; c < in.cols; ++c) {
      const bool got = back.at<uchar>(r, c), want = in.occupied.at<uchar>(r, c);
      if (got == want) continue;
      ++mismatched;
      // A wrong cell must sit on the boundary: within one cell of the other kind.
      EXPECT_NE(dilated.at<uchar>(r, c), eroded.at<uchar>(r, c))
          << "interior cell " << r << "," << c;
    }
  EXPECT_LT(mismatched, 0.01 * in.occupied_pixels) << mismatched << " cells differ";
  // Written and read back, the map is unchanged.
  write_map(in.map, tmp.path / "room.json");
  EXPECT_EQ(map_to_json(read_map(tmp.path / "room.json")), map_to_json(in.map));
}

TEST(RosImport, WithoutSimplificationTheRoundTripIsExact) {
  TempDir tmp;
  cv::Mat img = cluttered_room();
  img.at<uchar>(96, 61) = 254;  // no pinch: nothing is changed before tracing
  const fs::path yaml = write_ros_map(tmp.path, img);
  RosImportOptions options;
  options.simplify_px = 0.0;
  const RosImport in = import_ros_map(yaml, options);
  EXPECT_EQ(in.stats.pinches_filled, 0);
  const cv::Mat back = rasterize_like_image(in.map, in.cols, in.rows);
  EXPECT_EQ(cv::countNonZero(back != in.occupied), 0);
}

TEST(RosImport, UnknownSpaceCanBeFree) {
  TempDir tmp;
  const fs::path yaml = write_ros_map(tmp.path, cluttered_room());
  RosImportOptions options;
  options.unknown_is_occupied = false;
  const RosImport in = import_ros_map(yaml, options);
  const RosImport occ = import_ros_map(yaml, {});
  EXPECT_LT(in.occupied_pixels, occ.occupied_pixels);
  EXPECT_EQ(in.occupied.at<uchar>(2, 2), 0);
  EXPECT_EQ(occ.occupied.at<uchar>(2, 2), 1);
}

TEST(RosImport, NegateInvertsTheGreyLevels) {
  TempDir tmp;
  cv::Mat img(20, 20, CV_8U, cv::Scalar(0));                              // free when negated
  cv::rectangle(img, cv::Rect(5, 5, 4, 4), cv::Scalar(255), cv::FILLED);  // occupied
  std::string yaml_text;
  const fs::path yaml = write_ros_map(tmp.path, img);
  std::ofstream(yaml) << "image: room.pgm\nresolution: 0.1\norigin: [0, 0, 0]\nnegate: 1\n"
                         "occupied_thresh: 0.65\nfree_thresh: 0.196\n";
  const RosImport in = import_ros_map(yaml, {});
  ASSERT_EQ(in.map.obstacles.size(), 1u);
  EXPECT_NEAR(std::abs(signed_area(in.map.obstacles[0])), 0.16, 1e-9);
}

TEST(RosImport, BadFilesAreInputErrors) {
  TempDir tmp;
  const fs::path yaml = write_ros_map(tmp.path, cluttered_room());
  auto message = [&](const std::string& text) {
    std::ofstream(yaml) << text;
    try {
      import_ros_map(yaml, {});
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(message("image: room.pgm\norigin: [0,0,0]\nnegate: 0\noccupied_thresh: 0.65\n"
                    "free_thresh: 0.2\n")
                .find("resolution: missing"),
            std::string::npos);
  EXPECT_NE(message("image: nothere.pgm\nresolution: 0.05\norigin: [0,0,0]\nnegate: 0\n"
                    "occupied_thresh: 0.65\nfree_thresh: 0.2\n")
                .find("cannot read"),
            std::string::npos);
  EXPECT_NE(message("image: room.pgm\nresolution: -1\norigin: [0,0,0]\nnegate: 0\n"
                    "occupied_thresh: 0.65\nfree_thresh: 0.2\n")
                .find("resolution"),
            std::string::npos);
  EXPECT_NE(message("image: [unclosed\n").find("room.yaml"), std::string::npos);
  EXPECT_THROW(import_ros_map(tmp.path / "missing.yaml", {}), InputError);
}

// A building as map_saver would write it, 100 x 60 px at 5 cm, origin
// (-2, -1.5): unknown outside, a room with 2-pixel walls (columns 10-11 and
// 88-89, rows 10-11 and 48-49) and four doors: two in the left wall (rows
// 20-29, 36-41), one in the right wall (rows 25-34), one in the top wall
// (columns 40-49). Door edges in the map frame: left doors on x = -1.5, y in
// [0, 0.5] and [-0.6, -0.3]; right door on x = 2.5, y in [-0.25, 0.25]; top
// door on y = 1, x in [0, 0.5].
cv::Mat building() {
  cv::Mat img(60, 100, CV_8U, cv::Scalar(205));
  cv::rectangle(img, cv::Rect(10, 10, 80, 40), cv::Scalar(0), cv::FILLED);
  cv::rectangle(img, cv::Rect(12, 12, 76, 36), cv::Scalar(254), cv::FILLED);
  cv::rectangle(img, cv::Rect(10, 20, 2, 10), cv::Scalar(254), cv::FILLED);
  cv::rectangle(img, cv::Rect(10, 36, 2, 6), cv::Scalar(254), cv::FILLED);
  cv::rectangle(img, cv::Rect(88, 25, 2, 10), cv::Scalar(254), cv::FILLED);
  cv::rectangle(img, cv::Rect(40, 10, 10, 2), cv::Scalar(254), cv::FILLED);
  return img;
}

void expect_opening(const Map& map, const Opening& o, Vec2 from, Vec2 to) {
  EXPECT_NEAR(map.to_frame(o.from).x, from.x, 1e-9);
  EXPECT_NEAR(map.to_frame(o.from).y, from.y, 1e-9);
  EXPECT_NEAR(map.to_frame(o.to).x, to.x, 1e-9);
  EXPECT_NEAR(map.to_frame(o.to).y, to.y, 1e-9);
}

TEST(RosImport, FrameComesFromTheYamlOriginAndRoundTrips) {
  TempDir tmp;
  const fs::path yaml = write_ros_map(tmp.path, cluttered_room());
  const RosImport in = import_ros_map(yaml, {});
  EXPECT_EQ(in.map.frame.origin, (Vec2{-2.0, -1.5}));
  const fs::path file = tmp.path / "room.json";
  write_map(in.map, file);
  const nlohmann::ordered_json j = nlohmann::ordered_json::parse(std::ifstream(file));
  EXPECT_EQ(j["format"], "plumekit-map/2");
  EXPECT_NEAR(j["frame"]["origin"][0].get<double>(), -2.0, 1e-12);
  EXPECT_NEAR(j["frame"]["origin"][1].get<double>(), -1.5, 1e-12);
  // The file holds map-frame coordinates: the default inlet is the left wall, x = -2.
  EXPECT_NEAR(j["openings"][0]["from"][0].get<double>(), -2.0, 1e-12);
  EXPECT_NEAR(j["openings"][0]["to"][1].get<double>(), -1.5 + 6.0, 1e-12);
  const Map back = read_map(file);
  EXPECT_EQ(back.frame.origin, in.map.frame.origin);
  EXPECT_DOUBLE_EQ(back.width, in.map.width);
  EXPECT_DOUBLE_EQ(back.height, in.map.height);
  // The same arena: read back, it rasterizes to the same pixels.
  EXPECT_EQ(cv::countNonZero(rasterize_like_image(back, in.cols, in.rows) !=
                             rasterize_like_image(in.map, in.cols, in.rows)),
            0);
}

// A real floor's origin is often a float32 off a whole micrometre (-9.53674e-07):
// what import-ros writes, plumekit reads back, as the same map.
TEST(RosImport, AnOriginOffTheMicrometreReadsBackAsTheSameMap) {
  TempDir tmp;
  cv::imwrite((tmp.path / "floor.pgm").string(), building());
  std::ofstream(tmp.path / "floor.yaml")
      << "image: floor.pgm\nresolution: 0.05\norigin: [-9.53674e-07, -9.53674e-07, 0.0]\n"
         "negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n";
  const RosImport in = import_ros_map(tmp.path / "floor.yaml", {});
  EXPECT_EQ(in.ros_origin, (Vec2{-9.53674e-07, -9.53674e-07}));  // reported as the YAML says
  EXPECT_EQ(in.map.frame.origin, (Vec2{-1e-06, -1e-06}));
  const fs::path file = tmp.path / "floor.json";
  write_map(in.map, file);
  const Map back = read_map(file);  // validates: every wall vertex inside the arena
  EXPECT_EQ(map_to_json(back), map_to_json(in.map));
  EXPECT_EQ(map_file_text(back, "x"), map_file_text(in.map, "x"));
  // A file written before the origin was rounded reads too, on the same arena.
  const std::string old_text = R"({"format": "plumekit-map/2", "name": "t",
      "frame": {"origin": [-9.53674e-07, 0]}, "size": [5, 3],
      "openings": [{"kind": "inlet", "from": [-1e-06, 0], "to": [-1e-06, 3], "speed": 1},
                   {"kind": "outlet", "from": [4.999999, 0], "to": [4.999999, 3]}],
      "obstacles": [[[-1e-06, 0], [0.999999, 0], [0.999999, 1], [-1e-06, 1]]]})";
  const Map old = parse_map(old_text, "old.json");
  EXPECT_EQ(old.obstacles[0][0], (Vec2{0, 0}));
}

TEST(RosImport, TypedOpeningsSnapOntoDoorsInTheMapFrame) {
  TempDir tmp;
  const fs::path yaml = write_ros_map(tmp.path, building());
  RosImportOptions options;
  // Typed as a user would: up to a pixel off across, a little long or short.
  options.inlets = {"-1.47,-0.03,-1.47,0.53,0.5,parabolic", "-1.5,-0.6,-1.5,-0.3"};
  options.outlets = {"2.52,-0.3,2.52,0.3", "0.02,0.98,0.48,0.98"};
  const RosImport in = import_ros_map(yaml, options);
  EXPECT_FALSE(in.default_openings);
  ASSERT_EQ(in.map.openings.size(), 4u);
  const Map& map = in.map;
  expect_opening(map, map.openings[0], {-1.5, 0.0}, {-1.5, 0.5});
  EXPECT_EQ(map.openings[0].speed, 0.5);
  EXPECT_EQ(map.openings[0].profile, Profile::Parabolic);
  expect_opening(map, map.openings[1], {-1.5, -0.6}, {-1.5, -0.3});
  EXPECT_EQ(map.openings[1].speed, 1.0);
  expect_opening(map, map.openings[2], {2.5, -0.25}, {2.5, 0.25});
  EXPECT_FALSE(map.openings[2].is_inlet());
  expect_opening(map, map.openings[3], {0.0, 1.0}, {0.5, 1.0});
  EXPECT_NEAR(in.snapped[0].shift_m, -0.03, 1e-9);
  EXPECT_NEAR(in.snapped[0].trimmed_m, 0.06, 1e-9);
  // On obstacle edges, not the arena's walls; air can cross the building.
  for (const Opening& o : map.openings)
    EXPECT_FALSE(map.wall_of(o).has_value());
  EXPECT_TRUE(in.free_space.inlet_reaches_outlet());
  EXPECT_TRUE(in.warnings.empty()) << in.warnings.front();
  const fs::path file = tmp.path / "building.json";
  write_map(map, file);
  const Map back = read_map(file);
  ASSERT_EQ(back.openings.size(), 4u);
  EXPECT_TRUE(map_grid_check(back, 0.05).inlet_reaches_outlet);
}

std::string option_error(const fs::path& yaml, const RosImportOptions& options,
                         std::string* field = nullptr) {
  try {
    import_ros_map(yaml, options);
  } catch (const OptionError& e) {
    if (field) *field = e.field();
    return e.what();
  }
  return "";
}

TEST(RosImport, OpeningsFarFromAnyBoundaryAreRefused) {
  TempDir tmp;
  const fs::path yaml = write_ros_map(tmp.path, building());
  RosImportOptions options;
  options.inlets = {"-1.5,0,-1.5,0.5"};
  options.outlets = {"0,0,0.5,0"};  // in the middle of the room
  std::string field;
  std::string message = option_error(yaml, options, &field);
  EXPECT_EQ(field, "ros.outlets");
  EXPECT_NE(message.find("'0,0,0.5,0'"), std::string::npos) << message;
  EXPECT_NE(message.find("no boundary of the free space"), std::string::npos) << message;
  options.outlets = {"0,0,1,1"};
  EXPECT_NE(option_error(yaml, options).find("not parallel to an axis"), std::string::npos);
  options.outlets = {"2.5,-0.25,2.5"};
  EXPECT_NE(option_error(yaml, options).find("expected X1,Y1,X2,Y2"), std::string::npos);
  options.outlets = {"2.5,-0.25,2.5,0.25"};
  options.inlets = {"-1.5,0,-1.5,0.5,1,turbulent"};
  EXPECT_NE(option_error(yaml, options).find("profile 'turbulent'"), std::string::npos);
  // Faster than the incompressible flow holds: refused by the option, not at the flow.
  options.inlets = {"-1.5,0,-1.5,0.5,1e9"};
  message = option_error(yaml, options, &field);
  EXPECT_EQ(field, "ros.inlets");
  EXPECT_NE(message.find("'-1.5,0,-1.5,0.5,1e9': the speed 1e9 m/s is too fast"), std::string::npos)
      << message;
  EXPECT_NE(message.find("at most 100 m/s"), std::string::npos) << message;
  EXPECT_NE(message.find("Mach 0.3"), std::string::npos) << message;
  options.inlets = {"-1.5,0,-1.5,0.5,100"};
  EXPECT_EQ(option_error(yaml, options), "");
  options.inlets = {"-1.5,0,-1.5,0.5", "-1.5,0.1,-1.5,0.4,2"};  // the same door twice
  message = option_error(yaml, options, &field);
  EXPECT_EQ(field, "ros.inlets");
  EXPECT_NE(message.find("overlaps ros.inlets '-1.5,0,-1.5,0.5'"), std::string::npos) << message;
  options.outlets.clear();
  option_error(yaml, options, &field);
  EXPECT_EQ(field, "ros.outlets");
}

TEST(RosImport, ClosesGapsNarrowerThanTheSizeAndReportsThem) {
  // Two blocks 1 px apart and two 3 px apart, far from the edge; unknown free.
  cv::Mat occ(40, 60, CV_8U, cv::Scalar(0));
  occ(cv::Rect(10, 10, 5, 10)).setTo(1);
  occ(cv::Rect(16, 10, 5, 10)).setTo(1);  // gap of 1 px (5 cm)
  occ(cv::Rect(35, 10, 5, 10)).setTo(1);
  occ(cv::Rect(43, 10, 5, 10)).setTo(1);  // gap of 3 px (15 cm)
  cv::Mat closed = occ.clone();
  const GapClosing g = close_gaps(closed, 0.1 / 0.05);  // narrower than 10 cm: 1 px
  EXPECT_EQ(g.radius_px, 1);
  EXPECT_EQ(g.gaps_closed, 1);
  EXPECT_EQ(g.pixels_filled, 10);
  EXPECT_EQ(g.regions_joined, 1);
  EXPECT_EQ(closed.at<uchar>(15, 15), 1);
  EXPECT_EQ(closed.at<uchar>(15, 41), 0);
  closed = occ.clone();
  const GapClosing wide = close_gaps(closed, 0.2 / 0.05);  // narrower than 20 cm: up to 3 px
  EXPECT_EQ(wide.gaps_closed, 2);
  EXPECT_EQ(wide.pixels_filled, 40);
  EXPECT_EQ(wide.regions_joined, 2);
  closed = occ.clone();
  EXPECT_EQ(close_gaps(closed, 1.0).pixels_filled, 0);  // a gap of 1 px is not narrower
  EXPECT_EQ(cv::countNonZero(closed != occ), 0);
  // A passage of 1 px between a block and the image's edge (the arena wall) closes too.
  cv::Mat edge(20, 20, CV_8U, cv::Scalar(0));
  edge(cv::Rect(1, 5, 5, 5)).setTo(1);
  EXPECT_EQ(close_gaps(edge, 2.0).pixels_filled, 5);
}

TEST(RosImport, ImportReportsClosedGapsAndDroppedSpecks) {
  TempDir tmp;
  cv::Mat img = building();
  img(cv::Rect(30, 20, 6, 10)).setTo(0);  // a shelf 1 px from another
  img(cv::Rect(37, 20, 6, 10)).setTo(0);
  img.at<uchar>(40, 60) = 0;  // specks of 1 and 2 pixels
  img(cv::Rect(70, 40, 2, 1)).setTo(0);
  const fs::path yaml = write_ros_map(tmp.path, img);
  const RosImport plain = import_ros_map(yaml, {});
  RosImportOptions options;
  options.close_gaps_m = 0.1;
  options.min_area_px = 3;
  const RosImport in = import_ros_map(yaml, options);
  EXPECT_EQ(in.gaps.gaps_closed, 1);
  EXPECT_EQ(in.gaps.pixels_filled, 10);
  EXPECT_EQ(in.gaps.regions_joined, 1);
  EXPECT_EQ(in.specks.specks, 2);
  EXPECT_EQ(in.specks.pixels, 3);
  EXPECT_EQ(in.occupied.at<uchar>(40, 60), 0);
  EXPECT_EQ(in.occupied.at<uchar>(25, 36), 1);
  EXPECT_EQ(in.occupied_pixels, plain.occupied_pixels + 10 - 3);
  EXPECT_EQ(in.map.obstacles.size() + 1 + 2, plain.map.obstacles.size());
}

TEST(RosImport, OfficeByDefaultSaysWhichRegionIsSealedAndHowToOpenIt) {
  const fs::path yaml = fs::path(PLUMEKIT_DATA_DIR) / "ros" / "office.yaml";
  const RosImport in = import_ros_map(yaml, {});
  EXPECT_FALSE(in.free_space.inlet_reaches_outlet());
  EXPECT_EQ(in.free_space.inlet_cells, 0);
  std::string all;
  for (const std::string& w : in.warnings)
    all += w + "\n";
  EXPECT_NE(all.find("no free path from any inlet to any outlet"), std::string::npos) << all;
  EXPECT_NE(all.find("no inlet opens into free space"), std::string::npos) << all;
  EXPECT_NE(all.find("largest sealed free region (48.8 m²"), std::string::npos) << all;
  EXPECT_NE(all.find("ros.unknown free"), std::string::npos) << all;
  EXPECT_NE(all.find("ros.inlets / ros.outlets"), std::string::npos) << all;
  // The region's point is in the map frame, in the free room.
  const FreeRegion& room = in.free_space.regions.front();
  EXPECT_TRUE(in.map.is_free(room.point));
  EXPECT_FALSE(room.inlet || room.outlet);
  // Unknown space free: the doors open onto the arena's walls, and air crosses.
  RosImportOptions free;
  free.unknown_is_occupied = false;
  const RosImport open = import_ros_map(yaml, free);
  EXPECT_TRUE(open.free_space.inlet_reaches_outlet());
  EXPECT_TRUE(open.warnings.empty());
  // So does the default map with the doors as openings.
  RosImportOptions doors;
  doors.inlets = {"0,1.8,0,3.4"};
  doors.outlets = {"11.25,1.0,11.25,4.2"};
  const RosImport through = import_ros_map(yaml, doors);
  EXPECT_TRUE(through.free_space.inlet_reaches_outlet());
  expect_opening(through.map, through.map.openings[0], {0.0, 1.85}, {0.0, 3.35});
  expect_opening(through.map, through.map.openings[1], {11.2, 1.1}, {11.2, 4.1});
}

TEST(RosImport, AnOpeningOnARaggedFaceSurvivesSimplification) {
  // A block whose top face has a one-pixel jog: Douglas-Peucker at 0.75 px
  // smooths the face into one slanted edge, which would take the inlet on
  // the face's left half off the outline. The inlet's stretch must stay.
  TempDir tmp;
  cv::Mat img(60, 100, CV_8U, cv::Scalar(254));
  img(cv::Rect(10, 30, 30, 30)).setTo(0);  // top face y = 1.5 m, x in [0.5, 2]
  img(cv::Rect(40, 29, 30, 31)).setTo(0);  // top face y = 1.55 m, x in [2, 3.5]
  const fs::path yaml = write_ros_map(tmp.path, img);
  std::ofstream(yaml) << "image: room.pgm\nresolution: 0.05\norigin: [0, 0, 0]\nnegate: 0\n"
                         "occupied_thresh: 0.65\nfree_thresh: 0.196\n";
  RosImportOptions options;
  options.inlets = {"0.75,1.5,1.75,1.5"};
  options.outlets = {"5,0.5,5,2.5"};  // the right wall
  const RosImport in = import_ros_map(yaml, options);
  expect_opening(in.map, in.map.openings[0], {0.75, 1.5}, {1.75, 1.5});
  // No fallback to exact outlines was needed.
  EXPECT_TRUE(in.warnings.empty()) << in.warnings.front();
  EXPECT_TRUE(in.free_space.inlet_reaches_outlet());
  EXPECT_EQ(in.map.inward_normal(in.map.openings[0]), (Vec2{0.0, 1.0}));
}

TEST(RosImport, NonZeroYawIsIgnoredWithAWarning) {
  TempDir tmp;
  const fs::path yaml = write_ros_map(tmp.path, building());
  std::ofstream(yaml) << "image: room.pgm\nresolution: 0.05\norigin: [1.0, 2.0, 0.5]\n"
                         "negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n";
  const RosImport in = import_ros_map(yaml, {});
  EXPECT_EQ(in.map.frame.origin, (Vec2{1.0, 2.0}));
  EXPECT_NE(in.warnings.front().find("yaw (0.5 rad) is ignored"), std::string::npos);
}

}  // namespace
}  // namespace plumekit
