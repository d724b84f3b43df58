#pragma once
// Pixel-level repairs of an occupancy image before it becomes polygons:
// closing gaps narrower than a size (so that no passage is narrower than the
// flow's cells) and dropping specks (sensor noise). Each returns what it
// changed, for the import's report.
#include <opencv2/core.hpp>

namespace plumekit {

struct GapClosing {
  int radius_px = 0;  // the closing's square is 2 * radius + 1 pixels
  int pixels_filled = 0;
  int gaps_closed = 0;     // 8-connected groups of filled pixels
  int regions_joined = 0;  // occupied regions before minus after
};

// Morphological closing of `occupied` (CV_8U, non-zero occupied) with a
// (2r+1)-pixel square, r = ceil(w / 2) for the widest gap w that is narrower
// than `gap_px` pixels: every free passage narrower than gap_px pixels between
// occupied regions, or between one and the image's edge (the arena's walls),
// is filled. gap_px <= 1 changes nothing.
GapClosing close_gaps(cv::Mat& occupied, double gap_px);

struct SpeckDrop {
  int specks = 0;
  int pixels = 0;
};

// Clears every 4-connected occupied region of fewer than `min_area_px` pixels.
SpeckDrop drop_specks(cv::Mat& occupied, double min_area_px);

}  // namespace plumekit
