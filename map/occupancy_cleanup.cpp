#include "map/occupancy_cleanup.hpp"

#include <cmath>

#include <opencv2/imgproc.hpp>

namespace plumekit {

namespace {

int region_count(const cv::Mat& mask) {
  cv::Mat labels;
  return cv::connectedComponents(mask != 0, labels, 4, CV_32S) - 1;
}

}  // namespace

GapClosing close_gaps(cv::Mat& occupied, double gap_px) {
  GapClosing g;
  // Gaps of w whole pixels with w < gap_px are closed (the slack absorbs the
  // round-off of metres / resolution, e.g. 0.2 / 0.05).
  const int widest = static_cast<int>(std::ceil(gap_px - 1e-9)) - 1;
  if (widest < 1) return g;
  g.radius_px = (widest + 1) / 2;
  const int r = g.radius_px;
  const cv::Mat before = occupied != 0;
  // The image's edge is the arena's wall: pad with occupied pixels so that a
  // passage between an obstacle and the wall closes like one between obstacles.
  cv::Mat padded, closed;
  cv::copyMakeBorder(before, padded, r, r, r, r, cv::BORDER_CONSTANT, 255);
  cv::morphologyEx(padded, closed, cv::MORPH_CLOSE,
                   cv::getStructuringElement(cv::MORPH_RECT, {2 * r + 1, 2 * r + 1}), {-1, -1}, 1,
                   cv::BORDER_CONSTANT, 0);
  const cv::Mat after = closed(cv::Rect(r, r, occupied.cols, occupied.rows)) != 0;
  const cv::Mat filled = after & ~before;
  g.pixels_filled = cv::countNonZero(filled);
  if (g.pixels_filled == 0) return g;
  cv::Mat labels;
  g.gaps_closed = cv::connectedComponents(filled, labels, 8, CV_32S) - 1;
  g.regions_joined = region_count(before) - region_count(after);
  occupied.setTo(1, after);
  return g;
}

SpeckDrop drop_specks(cv::Mat& occupied, double min_area_px) {
  SpeckDrop d;
  if (min_area_px <= 1) return d;
  cv::Mat labels, stats, centroids;
  const int n =
      cv::connectedComponentsWithStats(occupied != 0, labels, stats, centroids, 4, CV_32S);
  std::vector<uchar> drop(n, 0);
  for (int k = 1; k < n; ++k) {
    const int area = stats.at<int>(k, cv::CC_STAT_AREA);
    if (area >= min_area_px) continue;
    drop[k] = 1;
    ++d.specks;
    d.pixels += area;
  }
  if (d.specks == 0) return d;
  for (int r = 0; r < occupied.rows; ++r)
    for (int c = 0; c < occupied.cols; ++c)
      if (drop[labels.at<int>(r, c)]) occupied.at<uchar>(r, c) = 0;
  return d;
}

}  // namespace plumekit
