#pragma once
// Openings typed by a user on a ROS occupancy image: "X1,Y1,X2,Y2[,SPEED[,PROFILE]]"
// in the map frame, snapped onto the nearest straight stretch of the free
// space's boundary (pixel edges with a free pixel on one side and an occupied
// pixel or the image's edge on the other), since no one can type the exact
// pixel edges of a door.
#include <string>

#include <opencv2/core.hpp>

#include "map/map.hpp"

namespace plumekit {

// An opening as typed: `field` names where it came from ("ros.inlets"),
// `text` is the value, `from`/`to` are map-frame points.
struct OpeningRequest {
  std::string field;
  std::string text;
  OpeningKind kind = OpeningKind::Inlet;
  Vec2 from, to;
  double speed = 1.0;
  Profile profile = Profile::Uniform;
};

// Parses "X1,Y1,X2,Y2" (outlets) or "X1,Y1,X2,Y2[,SPEED[,PROFILE]]" (inlets;
// speed in m/s, default 1; profile uniform or parabolic). OptionError(field)
// naming the value when it is malformed.
OpeningRequest parse_opening(const std::string& text, OpeningKind kind, const std::string& field);

// The image an opening is snapped on: occupancy (CV_8U, non-zero occupied,
// row 0 at the top), metres per pixel, and the map-frame position of the
// image's lower-left corner.
struct OccupancyImage {
  cv::Mat occupied;
  double resolution = 0.0;
  Vec2 origin;
};

struct SnappedOpening {
  OpeningRequest request;
  Opening opening;         // arena frame, on pixel edges
  double shift_m = 0.0;    // how far the line moved across
  double trimmed_m = 0.0;  // requested length minus snapped length (negative: extended)
};

// Snaps `request` onto the boundary: the pixel-edge line within `tolerance_px`
// of the request (across) with the most boundary along the request, then the
// longest run of boundary on it with one free side; an end of the run that
// lies within tolerance_px of the stretch's own end (a door's jamb) moves
// onto it, an end where the stretch runs on stays where it was typed.
// OptionError naming the request's field and value when the request is not
// roughly axis-parallel, is shorter than a pixel, or no boundary lies near it.
SnappedOpening snap_opening(const OccupancyImage& image, const OpeningRequest& request,
                            double tolerance_px);

}  // namespace plumekit
