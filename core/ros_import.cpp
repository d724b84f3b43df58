#include "core/ros_import.hpp"

#include <cctype>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <stdexcept>
#include <unordered_map>

#include <yaml-cpp/yaml.h>
#include <opencv2/imgproc.hpp>

#include "core/error.hpp"
#include "core/image_io.hpp"
#include "core/map_json.hpp"
#include "core/memory_limit.hpp"
#include "core/option_check.hpp"

namespace plumekit {

namespace {

// Sets one free pixel of each 2x2 window whose occupied pixels touch only
// diagonally, until none is left. Returns the number of pixels set.
int fill_diagonal_pinches(cv::Mat& m) {
  int filled = 0;
  for (bool changed = true; changed;) {
    changed = false;
    for (int r = 0; r + 1 < m.rows; ++r) {
      for (int c = 0; c + 1 < m.cols; ++c) {
        uchar &a = m.at<uchar>(r, c), &b = m.at<uchar>(r, c + 1);
        uchar &d = m.at<uchar>(r + 1, c), &e = m.at<uchar>(r + 1, c + 1);
        if (a && e && !b && !d) {
          b = 1;
        } else if (b && d && !a && !e) {
          a = 1;
        } else {
          continue;
        }
        ++filled;
        changed = true;
      }
    }
  }
  return filled;
}

// The outline of a 4-connected, hole-free, pinch-free region (CV_8U, non-zero
// inside), as pixel-corner coordinates (x = column, y = row), collinear
// vertices removed. Each pixel side facing the outside is one directed edge,
// oriented the same way round every pixel, so the edges chain into one loop.
std::vector<cv::Point> trace_outline(const cv::Mat& region) {
  auto inside = [&](int r, int c) {
    return r >= 0 && c >= 0 && r < region.rows && c < region.cols && region.at<uchar>(r, c);
  };
  auto key = [](cv::Point p) {
    return (static_cast<std::int64_t>(p.x) << 32) ^ static_cast<std::uint32_t>(p.y);
  };
  std::unordered_map<std::int64_t, cv::Point> next;
  cv::Point start(-1, -1);
  for (int r = 0; r < region.rows; ++r) {
    for (int c = 0; c < region.cols; ++c) {
      if (!inside(r, c)) continue;
      const cv::Point tl(c, r), tr(c + 1, r), br(c + 1, r + 1), bl(c, r + 1);
      if (!inside(r - 1, c)) next[key(tl)] = tr;
      if (!inside(r, c + 1)) next[key(tr)] = br;
      if (!inside(r + 1, c)) next[key(br)] = bl;
      if (!inside(r, c - 1)) next[key(bl)] = tl;
      if (start.x < 0) start = tl;
    }
  }
  std::vector<cv::Point> loop;
  cv::Point p = start;
  do {
    loop.push_back(p);
    p = next.at(key(p));
  } while (p != start && loop.size() <= next.size());
  if (loop.size() != next.size())
    throw std::logic_error("outline tracing: region has more than one boundary loop");

  std::vector<cv::Point> corners;
  const std::size_t n = loop.size();
  for (std::size_t i = 0; i < n; ++i) {
    const cv::Point in = loop[i] - loop[(i + n - 1) % n], out = loop[(i + 1) % n] - loop[i];
    if (in.x * out.y - in.y * out.x != 0) corners.push_back(loop[i]);
  }
  return corners;
}

Polygon to_world(const std::vector<cv::Point>& pts, double resolution, int rows) {
  Polygon poly;
  for (const cv::Point& p : pts)
    poly.push_back({p.x * resolution, (rows - p.y) * resolution});
  return poly;
}

// Outline, then Douglas-Peucker with a tolerance small enough to keep it simple.
Polygon simplified_outline(const cv::Mat& region, cv::Point offset, double resolution, int rows,
                           double simplify_px) {
  std::vector<cv::Point> outline = trace_outline(region);
  for (cv::Point& p : outline)
    p += offset;
  for (double eps = simplify_px; eps >= 0.25; eps *= 0.5) {
    std::vector<cv::Point> simple;
    cv::approxPolyDP(outline, simple, eps, true);
    Polygon poly = to_world(simple, resolution, rows);
    if (!simplicity_fault(poly)) return poly;
  }
  return to_world(outline, resolution, rows);
}

// Splits `region` (one 4-connected component, CV_8U) until no piece encloses
// free space, then appends each piece's outline to `out`.
void region_to_polygons(const cv::Mat& region, cv::Point offset, double resolution, int rows,
                        const RosImportOptions& options, MaskPolygonStats& stats,
                        std::vector<Polygon>& out) {
  // Flood the outside from a one-pixel frame; free pixels it misses are enclosed.
  cv::Mat padded;
  cv::copyMakeBorder(region, padded, 1, 1, 1, 1, cv::BORDER_CONSTANT, 0);
  cv::Mat flooded = padded.clone();
  cv::floodFill(flooded, cv::Point(0, 0), 2, nullptr, 0, 0, 4);
  cv::Point hole(-1, -1);
  for (int r = 0; r < flooded.rows && hole.x < 0; ++r)
    for (int c = 0; c < flooded.cols; ++c)
      if (flooded.at<uchar>(r, c) == 0) {
        hole = {c, r};
        break;
      }
  if (hole.x < 0) {
    out.push_back(simplified_outline(region, offset, resolution, rows, options.simplify_px));
    return;
  }
  // Cut along the middle row of this enclosed area: both halves open it.
  cv::Rect extent;
  cv::floodFill(flooded, hole, 3, &extent, 0, 0, 4);
  const int cut = extent.y + extent.height / 2 - 1;  // last row of the upper half (unpadded)
  ++stats.cuts;
  for (const cv::Range rows_part : {cv::Range(0, cut + 1), cv::Range(cut + 1, region.rows)}) {
    if (rows_part.empty()) continue;
    const cv::Mat part = region.rowRange(rows_part);
    cv::Mat labels;
    const int n = cv::connectedComponents(part, labels, 4, CV_32S);
    for (int k = 1; k < n; ++k) {
      const cv::Mat piece = labels == k;
      const cv::Rect box = cv::boundingRect(piece);
      cv::Mat sub = piece(box) / 255;
      region_to_polygons(sub, offset + cv::Point(box.x, box.y + rows_part.start), resolution, rows,
                         options, stats, out);
    }
  }
}

// Width and height from a PNG's IHDR or a PGM's header, without decoding the
// pixels; {0, 0} when the header is neither (the reader then says why).
std::pair<double, double> image_dimensions(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  char head[24] = {};
  if (!in.read(head, sizeof head)) return {0, 0};
  auto u8 = [&](int k) { return static_cast<double>(static_cast<unsigned char>(head[k])); };
  if (std::string(head + 1, 3) == "PNG" && std::string(head + 12, 4) == "IHDR")
    return {((u8(16) * 256 + u8(17)) * 256 + u8(18)) * 256 + u8(19),
            ((u8(20) * 256 + u8(21)) * 256 + u8(22)) * 256 + u8(23)};
  if (head[0] == 'P' && (head[1] == '5' || head[1] == '2')) {
    in.clear();
    in.seekg(2);
    double dims[2] = {0, 0};
    for (double& d : dims) {
      for (int c = in.peek(); c == '#' || std::isspace(c); c = in.peek())
        c == '#' ? static_cast<void>(in.ignore(1 << 16, '\n')) : static_cast<void>(in.get());
      if (!(in >> d)) return {0, 0};
    }
    return {dims[0], dims[1]};
  }
  return {0, 0};
}

// Peak bytes per pixel of an import: the grey image, the occupancy and its
// mask, the 32-bit component labels, and the per-region copies and outlines.
constexpr double kImportBytesPerPixel = 24.0;

template <class T>
T yaml_value(const YAML::Node& doc, const char* key, const std::string& origin) {
  const YAML::Node node = doc[key];
  if (!node) throw InputError(origin + ": " + key + ": missing (required by map_server)");
  try {
    return node.as<T>();
  } catch (const YAML::Exception&) {
    throw InputError(origin + ": " + key + ": has the wrong type");
  }
}

}  // namespace

std::vector<Polygon> occupancy_to_polygons(const cv::Mat& occupied, double resolution,
                                           const RosImportOptions& options,
                                           MaskPolygonStats* stats_out) {
  MaskPolygonStats stats;
  cv::Mat mask = occupied != 0;
  mask /= 255;
  stats.pinches_filled = fill_diagonal_pinches(mask);

  std::vector<Polygon> polygons;
  cv::Mat labels, boxes, centroids;
  const int n = cv::connectedComponentsWithStats(mask, labels, boxes, centroids, 4, CV_32S);
  for (int k = 1; k < n; ++k) {
    if (boxes.at<int>(k, cv::CC_STAT_AREA) < options.min_area_px) {
      ++stats.specks_dropped;
      continue;
    }
    const cv::Rect box(boxes.at<int>(k, cv::CC_STAT_LEFT), boxes.at<int>(k, cv::CC_STAT_TOP),
                       boxes.at<int>(k, cv::CC_STAT_WIDTH), boxes.at<int>(k, cv::CC_STAT_HEIGHT));
    cv::Mat region = labels(box) == k;
    region /= 255;
    region_to_polygons(region, box.tl(), resolution, occupied.rows, options, stats, polygons);
  }
  if (stats_out) *stats_out = stats;
  return polygons;
}

RosImport import_ros_map(const std::filesystem::path& yaml_path, const RosImportOptions& options) {
  check_non_negative("ros.simplify_px", options.simplify_px, 10.0, "px", "the default is 0.75");
  check_non_negative("ros.min_area_px", options.min_area_px, 1e12, "px", "0 keeps every speck");
  const std::string origin = yaml_path.string();
  std::error_code ec;
  if (std::filesystem::is_directory(yaml_path, ec))
    throw InputError(origin + ": is a folder; name the map_server YAML file inside it");
  YAML::Node doc;
  try {
    doc = YAML::LoadFile(origin);
  } catch (const YAML::BadFile&) {
    throw InputError(origin + ": no such file, or not readable");
  } catch (const YAML::Exception& e) {
    throw InputError(origin + ": not valid YAML: " + e.what());
  }
  if (!doc.IsMap()) throw InputError(origin + ": expected a map_server YAML mapping");

  RosImport result;
  const auto image_name = yaml_value<std::string>(doc, "image", origin);
  result.resolution = yaml_value<double>(doc, "resolution", origin);
  if (!(std::isfinite(result.resolution) && result.resolution > 0))
    throw InputError(origin + ": resolution: must be a positive number of metres per pixel");
  const auto ros_origin = yaml_value<std::vector<double>>(doc, "origin", origin);
  if (ros_origin.size() != 3) throw InputError(origin + ": origin: expected [x, y, yaw]");
  result.ros_origin = {ros_origin[0], ros_origin[1]};
  result.ros_yaw = ros_origin[2];
  const bool negate = yaml_value<int>(doc, "negate", origin) != 0;
  const double occupied_thresh = yaml_value<double>(doc, "occupied_thresh", origin);
  const double free_thresh = yaml_value<double>(doc, "free_thresh", origin);
  if (!(free_thresh >= 0 && free_thresh <= occupied_thresh && occupied_thresh <= 1))
    throw InputError(origin + ": free_thresh, occupied_thresh: need 0 <= free <= occupied <= 1");
  const std::string mode = doc["mode"] ? yaml_value<std::string>(doc, "mode", origin) : "trinary";
  if (mode != "trinary" && mode != "scale" && mode != "raw")
    throw InputError(origin + ": mode: '" + mode + "' is not trinary, scale or raw");

  std::filesystem::path image_path(image_name);
  if (image_path.is_relative()) image_path = yaml_path.parent_path() / image_path;
  const auto [cols, rows] = image_dimensions(image_path);
  check_memory(cols * rows * kImportBytesPerPixel,
               origin + ": importing the " + compact(cols) + " x " + compact(rows) + " px image",
               "crop or downsample the image");
  const cv::Mat image = read_gray_image(image_path);
  if (image.empty())
    throw InputError(origin + ": image: cannot read '" + image_path.string() + "' as PGM/PNG");

  // map_server's rule: occupancy probability from the grey level.
  cv::Mat occupied(image.size(), CV_8U);
  for (int r = 0; r < image.rows; ++r) {
    for (int c = 0; c < image.cols; ++c) {
      const int v = image.at<uchar>(r, c);
      double p = 0.0;
      bool known = true;
      if (mode == "raw") {
        known = v <= 100;
        p = v / 100.0;
      } else {
        p = negate ? v / 255.0 : (255 - v) / 255.0;
        known = p > occupied_thresh || p < free_thresh;
      }
      occupied.at<uchar>(r, c) = known ? (p > occupied_thresh) : options.unknown_is_occupied;
    }
  }
  result.cols = image.cols;
  result.rows = image.rows;
  result.occupied_pixels = cv::countNonZero(occupied);
  result.occupied = occupied;

  result.map = default_arena(image.cols * result.resolution, image.rows * result.resolution);
  result.map.name = options.name.empty() ? yaml_path.stem().string() : options.name;
  result.map.obstacles = occupancy_to_polygons(occupied, result.resolution, options, &result.stats);
  validate_map(result.map, origin);
  return result;
}

}  // namespace plumekit
