#pragma once
// Import of ROS map_server maps (a YAML file naming a PGM/PNG occupancy image).
//
// Occupied pixels become obstacle polygons:
//  1. Threshold the image the way map_server does (negate, occupied_thresh,
//     free_thresh, mode); unknown pixels count as occupied unless told otherwise.
//  2. Fill one pixel of every diagonal-only contact, so every region's outline
//     is a simple polygon (a diagonal pinch would make it touch itself).
//  3. Cut each region that encloses free space into pieces along a pixel row
//     through the enclosed area, since map polygons have no holes.
//  4. Trace each region's outline along pixel edges, exactly, and simplify it
//     with OpenCV's Douglas-Peucker (approxPolyDP), shrinking the tolerance
//     when simplification would break simplicity.
// Pixel-edge outlines are used instead of cv::findContours because its chains
// run through boundary pixel centres: they thin every wall by one pixel and
// collapse one-pixel walls into zero-area loops.
#include <filesystem>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "core/map.hpp"

namespace plumekit {

struct RosImportOptions {
  double simplify_px = 0.75;        // Douglas-Peucker tolerance, in pixels
  bool unknown_is_occupied = true;  // unexplored space is not free to fly or drive in
  double min_area_px = 0.0;         // drop occupied specks smaller than this (pixels)
  std::string name;                 // map name; default: the YAML's file stem
};

struct MaskPolygonStats {
  int pinches_filled = 0;  // pixels set to remove diagonal-only contacts
  int cuts = 0;            // row cuts made to open enclosed free space
  int specks_dropped = 0;
};

struct RosImport {
  Map map;
  double resolution = 0.0;  // m per pixel
  Vec2 ros_origin;          // map frame position of the image's lower-left corner
  double ros_yaw = 0.0;     // rad; plumekit maps are axis-aligned, so this is reported only
  int cols = 0, rows = 0;
  int occupied_pixels = 0;
  cv::Mat occupied;  // CV_8U, 1 where occupied, row 0 at the top (image order)
  MaskPolygonStats stats;
};

RosImport import_ros_map(const std::filesystem::path& yaml_path, const RosImportOptions& options);

// Polygons (metres, y up) outlining the non-zero pixels of `occupied`
// (CV_8U, row 0 at the top as in images), `resolution` metres per pixel.
std::vector<Polygon> occupancy_to_polygons(const cv::Mat& occupied, double resolution,
                                           const RosImportOptions& options,
                                           MaskPolygonStats* stats = nullptr);

}  // namespace plumekit
