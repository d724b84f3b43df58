#pragma once
// Import of ROS map_server maps (a YAML file naming a PGM/PNG occupancy image).
//
// Occupied pixels become obstacle polygons:
//  1. Threshold the image the way map_server does (negate, occupied_thresh,
//     free_thresh, mode); unknown pixels count as occupied unless told otherwise.
//     Optionally drop specks, then close gaps narrower than a size
//     (map/occupancy_cleanup.hpp).
//  2. Fill one pixel of every diagonal-only contact, so every region's outline
//     is a simple polygon (a diagonal pinch would make it touch itself).
//  3. Cut each region that encloses free space into pieces along a pixel row
//     through the enclosed area, since map polygons have no holes.
//  4. Trace each region's outline along pixel edges, exactly, and simplify it
//     with OpenCV's Douglas-Peucker (approxPolyDP), shrinking the tolerance
//     when simplification would break simplicity. Outline points on an
//     opening are kept, so that the opening stays on the obstacle's edge.
//  5. Openings: the whole left wall an inlet and the whole right wall an
//     outlet, or the ones the user typed in the map frame, snapped onto the
//     boundary of the free space (map/opening_snap.hpp).
//  6. Check that air can cross the result (map/connectivity.hpp), and say
//     which region is sealed when it cannot.
// The map's frame origin is the YAML's origin (x, y). A non-zero yaw is
// ignored with a warning, as map_server and most ROS tools ignore it: the
// image is taken as axis-aligned in the map frame.
// Pixel-edge outlines are used instead of cv::findContours because its chains
// run through boundary pixel centres: they thin every wall by one pixel and
// collapse one-pixel walls into zero-area loops.
#include <filesystem>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "core/option_table.hpp"
#include "map/connectivity.hpp"
#include "map/map.hpp"
#include "map/occupancy_cleanup.hpp"
#include "map/opening_snap.hpp"

namespace plumekit {

struct RosImportOptions {
  double simplify_px = 0.75;        // Douglas-Peucker tolerance, in pixels
  bool unknown_is_occupied = true;  // unexplored space is not free to fly or drive in
  double min_area_px = 0.0;         // drop occupied specks smaller than this (pixels)
  double close_gaps_m = 0.0;        // close free gaps narrower than this (m); 0: none
  // Openings, map frame: "X1,Y1,X2,Y2[,SPEED[,PROFILE]]" (inlets), "X1,Y1,X2,Y2"
  // (outlets). None: the whole left wall is an inlet at 1 m/s and the whole
  // right wall an outlet. Otherwise at least one of each.
  std::vector<std::string> inlets;
  std::vector<std::string> outlets;
  double snap_px = 2.0;  // how far (pixels) a typed opening may move onto the boundary
  std::string name;      // map name; default: the YAML's file stem
};

// Its numbers' table (core/option_table.hpp): their checks, `map import-ros`'s flags, the Python
// properties and docs/options.md. The openings, the name and --unknown are bound by hand.
const OptionTable<RosImportOptions>& ros_import_option_table();

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
  int unknown_pixels = 0;
  // CV_8U, 1 where occupied, row 0 at the top (image order), after gap
  // closing, speck dropping and pinch filling: what the polygons outline.
  cv::Mat occupied;
  MaskPolygonStats stats;
  GapClosing gaps;
  SpeckDrop specks;
  bool default_openings = true;
  std::vector<SnappedOpening> snapped;  // the typed openings, as snapped
  int raster_mismatch_pixels = 0;       // pixels that differ when the map is rasterized back
  FreeSpace free_space;                 // at the image's resolution
  std::vector<std::string> warnings;    // may name option fields ("ros.unknown")
};

RosImport import_ros_map(const std::filesystem::path& yaml_path, const RosImportOptions& options);

// Sets one free pixel of each 2x2 window of `mask` (CV_8U, 0/1) whose
// occupied pixels touch only diagonally, until none is left; returns the count.
int fill_diagonal_pinches(cv::Mat& mask);

// Polygons (metres, y up) outlining the non-zero pixels of `occupied`
// (CV_8U, row 0 at the top as in images), `resolution` metres per pixel.
// Outline points on an opening of `keep_straight` (arena frame, on pixel
// edges) survive simplification, so the opening stays on the outline.
std::vector<Polygon> occupancy_to_polygons(const cv::Mat& occupied, double resolution,
                                           const RosImportOptions& options,
                                           MaskPolygonStats* stats = nullptr,
                                           const std::vector<Opening>& keep_straight = {});

}  // namespace plumekit
