#include "map/ros_import.hpp"

#include <cctype>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>
#include <tuple>
#include <unordered_map>

#include <yaml-cpp/yaml.h>
#include <opencv2/imgproc.hpp>

#include "core/error.hpp"
#include "core/image_io.hpp"
#include "core/memory_limit.hpp"
#include "core/option_check.hpp"
#include "map/map_json.hpp"
#include "map/rasterize.hpp"

namespace plumekit {

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

namespace {

// Opening stretches in pixel-corner coordinates (x = column edge, y = row edge
// from the top), whose outline points tracing keeps.
struct PixelSegment {
  bool vertical = false;
  int line = 0;
  int lo = 0, hi = 0;
  bool holds(cv::Point p) const {
    const int across = vertical ? p.x : p.y, along = vertical ? p.y : p.x;
    return across == line && along >= lo && along <= hi;
  }
};

// What tracing needs besides the region.
struct Tracing {
  double resolution = 0.0;
  int rows = 0;
  const RosImportOptions& options;
  MaskPolygonStats& stats;
  std::vector<PixelSegment> keep;
  bool holds(cv::Point p) const {
    for (const PixelSegment& k : keep)
      if (k.holds(p)) return true;
    return false;
  }
};

std::vector<PixelSegment> pixel_segments(const std::vector<Opening>& openings, double resolution,
                                         int rows) {
  std::vector<PixelSegment> out;
  for (const Opening& o : openings) {
    PixelSegment k;
    k.vertical = o.vertical();
    if (k.vertical) {
      k.line = static_cast<int>(std::lround(o.line() / resolution));
      k.lo = rows - static_cast<int>(std::lround(o.hi() / resolution));
      k.hi = rows - static_cast<int>(std::lround(o.lo() / resolution));
    } else {
      k.line = rows - static_cast<int>(std::lround(o.line() / resolution));
      k.lo = static_cast<int>(std::lround(o.lo() / resolution));
      k.hi = static_cast<int>(std::lround(o.hi() / resolution));
    }
    out.push_back(k);
  }
  return out;
}

// The outline of a 4-connected, hole-free, pinch-free region (CV_8U, non-zero
// inside), as pixel-corner coordinates (x = column, y = row), collinear
// vertices kept. Each pixel side facing the outside is one directed edge,
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
  return loop;
}

// The loop's corners, and every point `keep` holds.
std::vector<cv::Point> corners(const std::vector<cv::Point>& loop, const Tracing& t,
                               bool with_kept) {
  std::vector<cv::Point> out;
  const std::size_t n = loop.size();
  for (std::size_t i = 0; i < n; ++i) {
    const cv::Point in = loop[i] - loop[(i + n - 1) % n], next = loop[(i + 1) % n] - loop[i];
    if (in.x * next.y - in.y * next.x != 0 || (with_kept && t.holds(loop[i])))
      out.push_back(loop[i]);
  }
  return out;
}

// Douglas-Peucker between consecutive kept points (each chain alone, so every
// kept point stays), then collinear points dropped. Plain Douglas-Peucker
// when the outline holds no kept point.
std::vector<cv::Point> simplify_keeping(const std::vector<cv::Point>& outline, const Tracing& t,
                                        double eps) {
  std::vector<cv::Point> simple;
  std::size_t first = outline.size();
  for (std::size_t i = 0; i < outline.size() && first == outline.size(); ++i)
    if (t.holds(outline[i])) first = i;
  if (first == outline.size()) {
    cv::approxPolyDP(outline, simple, eps, true);
    return simple;
  }
  const std::size_t n = outline.size();
  std::vector<cv::Point> chain{outline[first]};
  for (std::size_t k = 1; k <= n; ++k) {
    const cv::Point p = outline[(first + k) % n];
    chain.push_back(p);
    if (!t.holds(p)) continue;
    std::vector<cv::Point> part;
    cv::approxPolyDP(chain, part, eps, false);
    simple.insert(simple.end(), part.begin(), part.end() - 1);
    chain = {p};
  }
  std::vector<cv::Point> out;
  const std::size_t m = simple.size();
  for (std::size_t i = 0; i < m; ++i) {
    const cv::Point in = simple[i] - simple[(i + m - 1) % m],
                    next = simple[(i + 1) % m] - simple[i];
    if (in.x * next.y - in.y * next.x != 0) out.push_back(simple[i]);
  }
  return out;
}

Polygon to_world(const std::vector<cv::Point>& pts, double resolution, int rows) {
  Polygon poly;
  for (const cv::Point& p : pts)
    poly.push_back({p.x * resolution, (rows - p.y) * resolution});
  return poly;
}

// Outline, then Douglas-Peucker with a tolerance small enough to keep it simple.
Polygon simplified_outline(const cv::Mat& region, cv::Point offset, const Tracing& t) {
  std::vector<cv::Point> loop = trace_outline(region);
  for (cv::Point& p : loop)
    p += offset;
  const std::vector<cv::Point> outline = corners(loop, t, true);
  for (double eps = t.options.simplify_px; eps >= 0.25; eps *= 0.5) {
    Polygon poly = to_world(simplify_keeping(outline, t, eps), t.resolution, t.rows);
    if (poly.size() >= 3 && !simplicity_fault(poly)) return poly;
  }
  return to_world(corners(loop, t, false), t.resolution, t.rows);
}

// Splits `region` (one 4-connected component, CV_8U) until no piece encloses
// free space, then appends each piece's outline to `out`.
void region_to_polygons(const cv::Mat& region, cv::Point offset, Tracing& t,
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
    out.push_back(simplified_outline(region, offset, t));
    return;
  }
  // Cut along the middle row of this enclosed area: both halves open it.
  cv::Rect extent;
  cv::floodFill(flooded, hole, 3, &extent, 0, 0, 4);
  const int cut = extent.y + extent.height / 2 - 1;  // last row of the upper half (unpadded)
  ++t.stats.cuts;
  for (const cv::Range rows_part : {cv::Range(0, cut + 1), cv::Range(cut + 1, region.rows)}) {
    if (rows_part.empty()) continue;
    const cv::Mat part = region.rowRange(rows_part);
    cv::Mat labels;
    const int n = cv::connectedComponents(part, labels, 4, CV_32S);
    for (int k = 1; k < n; ++k) {
      const cv::Mat piece = labels == k;
      const cv::Rect box = cv::boundingRect(piece);
      cv::Mat sub = piece(box) / 255;
      region_to_polygons(sub, offset + cv::Point(box.x, box.y + rows_part.start), t, out);
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
// masks, the 32-bit component labels, the per-region copies and outlines, and
// the check's label grid and free-region floods. Measured: Nav2's warehouse
// (1.68 Mpx) peaks at 188 MB of which 24 MB is the idle process, 97 B/px.
constexpr double kImportBytesPerPixel = 100.0;

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
                                           MaskPolygonStats* stats_out,
                                           const std::vector<Opening>& keep_straight) {
  MaskPolygonStats stats;
  cv::Mat mask = occupied != 0;
  mask /= 255;
  stats.pinches_filled = fill_diagonal_pinches(mask);

  Tracing t{resolution, occupied.rows, options, stats,
            pixel_segments(keep_straight, resolution, occupied.rows)};
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
    region_to_polygons(region, box.tl(), t, polygons);
  }
  if (stats_out) *stats_out = stats;
  return polygons;
}

const OptionTable<RosImportOptions>& ros_import_option_table() {
  using O = RosImportOptions;
  static const OptionTable<O> table{
      "ROS map import (RosImportOptions)",
      {{"ros.simplify_px", "--simplify", &O::simplify_px, non_negative(10.0, "px"),
        "Douglas-Peucker tolerance for obstacle outlines, in pixels"},
       {"ros.unknown_is_occupied",
        "",
        &O::unknown_is_occupied,
        {},
        "Unexplored pixels are obstacles (--unknown occupied|free)"},
       {"ros.min_area_px", "--min-area", &O::min_area_px, non_negative(1e12, "px"),
        "Drop occupied specks with fewer pixels than this", "0 keeps every speck"},
       {"ros.close_gaps_m", "--close-gaps", &O::close_gaps_m, non_negative(100.0, "m"),
        "Close free gaps narrower than this (m) between occupied regions or the image's edge "
        "(0: none)",
        "0 closes none"},
       {"ros.snap_px", "--snap", &O::snap_px, non_negative(100.0, "px"),
        "How far (pixels) a given opening may move onto the boundary"}}};
  return table;
}

namespace {

// What a map_server YAML file says.
struct RosYaml {
  std::filesystem::path image;  // resolved against the YAML's folder
  double resolution = 0.0;
  Vec2 origin;
  double yaw = 0.0;
  bool negate = false;
  double occupied_thresh = 0.65, free_thresh = 0.196;
  std::string mode = "trinary";
};

RosYaml read_ros_yaml(const std::filesystem::path& yaml_path) {
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

  RosYaml y;
  y.image = yaml_value<std::string>(doc, "image", origin);
  if (y.image.is_relative()) y.image = yaml_path.parent_path() / y.image;
  y.resolution = yaml_value<double>(doc, "resolution", origin);
  if (!(std::isfinite(y.resolution) && y.resolution > 0))
    throw InputError(origin + ": resolution: must be a positive number of metres per pixel");
  const auto ros_origin = yaml_value<std::vector<double>>(doc, "origin", origin);
  if (ros_origin.size() != 3) throw InputError(origin + ": origin: expected [x, y, yaw]");
  for (double v : ros_origin)
    if (!std::isfinite(v)) throw InputError(origin + ": origin: expected finite numbers");
  y.origin = {ros_origin[0], ros_origin[1]};
  y.yaw = ros_origin[2];
  y.negate = yaml_value<int>(doc, "negate", origin) != 0;
  y.occupied_thresh = yaml_value<double>(doc, "occupied_thresh", origin);
  y.free_thresh = yaml_value<double>(doc, "free_thresh", origin);
  if (!(y.free_thresh >= 0 && y.free_thresh <= y.occupied_thresh && y.occupied_thresh <= 1))
    throw InputError(origin + ": free_thresh, occupied_thresh: need 0 <= free <= occupied <= 1");
  if (doc["mode"]) y.mode = yaml_value<std::string>(doc, "mode", origin);
  if (y.mode != "trinary" && y.mode != "scale" && y.mode != "raw")
    throw InputError(origin + ": mode: '" + y.mode + "' is not trinary, scale or raw");
  return y;
}

// map_server's rule: occupancy probability from the grey level. Counts the unknown pixels.
cv::Mat threshold(const cv::Mat& image, const RosYaml& y, bool unknown_is_occupied, int& unknown) {
  cv::Mat occupied(image.size(), CV_8U);
  unknown = 0;
  for (int r = 0; r < image.rows; ++r) {
    for (int c = 0; c < image.cols; ++c) {
      const int v = image.at<uchar>(r, c);
      double p = 0.0;
      bool known = true;
      if (y.mode == "raw") {
        known = v <= 100;
        p = v / 100.0;
      } else {
        p = y.negate ? v / 255.0 : (255 - v) / 255.0;
        known = p > y.occupied_thresh || p < y.free_thresh;
      }
      unknown += !known;
      occupied.at<uchar>(r, c) = known ? (p > y.occupied_thresh) : unknown_is_occupied;
    }
  }
  return occupied;
}

void check_options(const RosImportOptions& o) {
  plumekit::validate(ros_import_option_table(), o);
  if (o.inlets.empty() != o.outlets.empty())
    throw OptionError(o.inlets.empty() ? "ros.inlets" : "ros.outlets",
                      "give at least one inlet and one outlet, or neither (the default: the whole "
                      "left wall an inlet, the whole right wall an outlet)");
}

std::string segment_text(const Map& map, const Opening& o) {
  std::ostringstream s;
  const Vec2 a = map.to_frame(o.from), b = map.to_frame(o.to);
  s << std::setprecision(6) << a.x << ',' << a.y << ',' << b.x << ',' << b.y;
  return s.str();
}

// The typed openings, snapped onto the occupancy's free-space boundary.
void add_typed_openings(RosImport& result, const RosImportOptions& options) {
  if (options.inlets.empty()) return;
  result.default_openings = false;
  Map& map = result.map;
  map.openings.clear();
  const OccupancyImage image{result.occupied, result.resolution, map.frame.origin};
  for (const auto& [list, field, kind] :
       {std::tuple{&options.inlets, "ros.inlets", OpeningKind::Inlet},
        std::tuple{&options.outlets, "ros.outlets", OpeningKind::Outlet}}) {
    for (const std::string& text : *list) {
      SnappedOpening s = snap_opening(image, parse_opening(text, kind, field), options.snap_px);
      for (const SnappedOpening& t : result.snapped) {
        const Opening &a = s.opening, &b = t.opening;
        if (a.vertical() == b.vertical() && a.line() == b.line() &&
            std::min(a.hi(), b.hi()) > std::max(a.lo(), b.lo()))
          throw OptionError(field, "'" + text + "' snaps to " + segment_text(map, a) +
                                       ", which overlaps " + t.request.field + " '" +
                                       t.request.text + "' (snapped to " + segment_text(map, b) +
                                       ")");
      }
      if (s.opening.length() < 0.5 * (s.opening.length() + s.trimmed_m))
        result.warnings.push_back(std::string(field) + " '" + text + "': only " +
                                  segment_text(map, s.opening) +
                                  " of it lies on the free space's boundary");
      map.openings.push_back(s.opening);
      result.snapped.push_back(std::move(s));
    }
  }
}

bool valid(const Map& map) {
  try {
    validate_map(map, "");
  } catch (const InputError&) {
    return false;
  }
  return true;
}

// Rasterizes the map back at the image's resolution: the pixels that differ,
// and whether air can cross it (with advice when it cannot).
void check_result(RosImport& result, const RosImportOptions& options) {
  if (result.ros_yaw != 0.0) {
    std::ostringstream s;
    s << "the YAML origin's yaw (" << result.ros_yaw << " rad) is ignored, as map_server "
      << "ignores it: map-frame coordinates are those of the unrotated image";
    result.warnings.push_back(s.str());
  }
  const Map& map = result.map;
  const GridShape shape{result.cols, result.rows, map.width, map.height};
  const Grid<std::uint8_t> labels = rasterize_labels(map, shape);
  result.raster_mismatch_pixels = 0;
  for (int r = 0; r < result.rows; ++r)
    for (int c = 0; c < result.cols; ++c)
      result.raster_mismatch_pixels +=
          (labels(c, result.rows - 1 - r) == kObstacle) != (result.occupied.at<uchar>(r, c) != 0);
  result.free_space = free_regions(labels);
  const bool unknown_hint = options.unknown_is_occupied && result.unknown_pixels > 0;
  for (std::string& w : sealed_map_advice(map, result.free_space, unknown_hint, true))
    result.warnings.push_back(std::move(w));
}

}  // namespace

RosImport import_ros_map(const std::filesystem::path& yaml_path, const RosImportOptions& options) {
  check_options(options);
  const RosYaml yaml = read_ros_yaml(yaml_path);
  const std::string origin = yaml_path.string();
  const auto [cols, rows] = image_dimensions(yaml.image);
  check_memory(cols * rows * kImportBytesPerPixel,
               origin + ": importing the " + compact(cols) + " x " + compact(rows) + " px image",
               "crop or downsample the image");
  const cv::Mat image = read_gray_image(yaml.image);
  if (image.empty())
    throw InputError(origin + ": image: cannot read '" + yaml.image.string() + "' as PGM/PNG");

  RosImport result;
  result.resolution = yaml.resolution;
  result.ros_origin = yaml.origin;
  result.ros_yaw = yaml.yaw;
  result.cols = image.cols;
  result.rows = image.rows;
  cv::Mat occupied = threshold(image, yaml, options.unknown_is_occupied, result.unknown_pixels);
  // Specks first: noise is not worth joining to its neighbours.
  result.specks = drop_specks(occupied, options.min_area_px);
  result.gaps = close_gaps(occupied, options.close_gaps_m / yaml.resolution);
  result.stats.pinches_filled = fill_diagonal_pinches(occupied);
  result.stats.specks_dropped = result.specks.specks;
  result.occupied_pixels = cv::countNonZero(occupied);
  result.occupied = occupied;

  Map& map = result.map;
  map = default_arena(image.cols * yaml.resolution, image.rows * yaml.resolution);
  map.name = options.name.empty() ? yaml_path.stem().string() : options.name;
  map.frame.origin = file_origin(yaml.origin);  // what its file holds (map_json.hpp)
  add_typed_openings(result, options);
  RosImportOptions tracing = options;
  tracing.min_area_px = 0;  // dropped above, on the pixels
  const std::vector<Opening> keep = result.default_openings ? std::vector<Opening>{} : map.openings;
  MaskPolygonStats stats;
  map.obstacles = occupancy_to_polygons(occupied, yaml.resolution, tracing, &stats, keep);
  if (!result.default_openings && !valid(map)) {
    // A simplified edge of a neighbouring obstacle reached an opening: trace exactly.
    tracing.simplify_px = 0.0;
    map.obstacles = occupancy_to_polygons(occupied, yaml.resolution, tracing, &stats, keep);
    result.warnings.push_back(
        "outlines traced without simplification, to keep the openings on "
        "the obstacles' edges");
  }
  result.stats.cuts = stats.cuts;
  validate_map(map, origin);
  check_result(result, options);
  return result;
}

}  // namespace plumekit
