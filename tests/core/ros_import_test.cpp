#include "core/ros_import.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "core/error.hpp"
#include "core/map_json.hpp"
#include "core/rasterize.hpp"

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

}  // namespace
}  // namespace plumekit
