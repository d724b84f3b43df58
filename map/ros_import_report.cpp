#include "map/ros_import_report.hpp"

#include <cmath>
#include <sstream>

namespace plumekit {

namespace {

using nlohmann::ordered_json;

ordered_json point(const Map& map, Vec2 arena) {
  const Vec2 p = map.to_frame(arena);
  return ordered_json::array({p.x, p.y});
}

ordered_json openings_json(const RosImport& in) {
  ordered_json list = ordered_json::array();
  for (std::size_t k = 0; k < in.map.openings.size(); ++k) {
    const Opening& o = in.map.openings[k];
    ordered_json j{
        {"kind", to_string(o.kind)}, {"from", point(in.map, o.from)}, {"to", point(in.map, o.to)}};
    if (o.is_inlet()) {
      j["speed"] = o.speed;
      j["profile"] = to_string(o.profile);
    }
    if (k < in.snapped.size()) {
      const SnappedOpening& s = in.snapped[k];
      j["requested"] = s.request.text;
      j["field"] = s.request.field;
      j["shift_m"] = s.shift_m;
      j["trimmed_m"] = s.trimmed_m;
    }
    list.push_back(std::move(j));
  }
  return list;
}

ordered_json regions_json(const RosImport& in) {
  ordered_json list = ordered_json::array();
  for (const FreeRegion& r : in.free_space.regions) {
    if (list.size() == 5) break;  // the largest few say where the air can go
    list.push_back({{"area_m2", r.area_m2},
                    {"point", point(in.map, r.point)},
                    {"inlet", r.inlet},
                    {"outlet", r.outlet}});
  }
  return list;
}

void opening_lines(const RosImport& in, std::ostringstream& s) {
  if (in.default_openings) {
    s << "\nopenings: the default, the whole left wall an inlet at 1 m/s and the whole right "
         "wall an outlet";
    return;
  }
  for (std::size_t k = 0; k < in.map.openings.size(); ++k) {
    const Opening& o = in.map.openings[k];
    const Vec2 a = in.map.to_frame(o.from), b = in.map.to_frame(o.to);
    s << '\n' << to_string(o.kind) << ' ' << a.x << ',' << a.y << ',' << b.x << ',' << b.y;
    if (o.is_inlet()) s << " at " << o.speed << " m/s " << to_string(o.profile);
    if (k < in.snapped.size()) {
      const SnappedOpening& sn = in.snapped[k];
      s << " (" << sn.request.field << " '" << sn.request.text << "': moved " << sn.shift_m
        << " m across, " << (sn.trimmed_m >= 0 ? "shortened by " : "lengthened by ")
        << std::abs(sn.trimmed_m) << " m)";
    }
  }
}

}  // namespace

ordered_json ros_import_json(const RosImport& in, const std::string& yaml, const std::string& out) {
  ordered_json j{{"ok", true},
                 {"yaml", yaml},
                 {"out", out},
                 {"format", in.map.format_version == 1 ? "plumekit-map/1" : "plumekit-map/2"},
                 {"image_px", {in.cols, in.rows}},
                 {"resolution_m", in.resolution},
                 {"size_m", {in.map.width, in.map.height}},
                 {"ros_origin", {in.ros_origin.x, in.ros_origin.y, in.ros_yaw}},
                 {"frame_origin", point(in.map, {0.0, 0.0})},
                 {"unknown_pixels", in.unknown_pixels},
                 {"occupied_pixels", in.occupied_pixels},
                 {"obstacles", in.map.obstacles.size()},
                 {"obstacle_vertices", vertex_count(in.map)}};
  j["gaps"] = {{"radius_px", in.gaps.radius_px},
               {"gaps_closed", in.gaps.gaps_closed},
               {"pixels_filled", in.gaps.pixels_filled},
               {"regions_joined", in.gaps.regions_joined}};
  j["specks"] = {{"dropped", in.specks.specks}, {"pixels", in.specks.pixels}};
  j["pinches_filled"] = in.stats.pinches_filled;
  j["enclosures_cut"] = in.stats.cuts;
  j["specks_dropped"] = in.stats.specks_dropped;
  j["raster_mismatch_pixels"] = in.raster_mismatch_pixels;
  j["default_openings"] = in.default_openings;
  j["openings"] = openings_json(in);
  j["inlet_reaches_outlet"] = in.free_space.inlet_reaches_outlet();
  j["free_regions"] = regions_json(in);
  j["warnings"] = in.warnings;
  return j;
}

std::string ros_import_text(const RosImport& in, const std::string& out) {
  std::ostringstream s;
  const Map& map = in.map;
  s << "wrote " << out << ": " << map.width << " x " << map.height << " m, " << map.obstacles.size()
    << " obstacles (" << vertex_count(map) << " vertices) from " << in.occupied_pixels
    << " occupied pixels; " << in.raster_mismatch_pixels << " pixels differ when rasterized back.\n"
    << "map frame: the arena's lower-left corner is (" << in.ros_origin.x << ", " << in.ros_origin.y
    << "), the YAML's origin; every coordinate in " << out << " is in the map frame";
  if (in.specks.specks > 0 || in.specks.pixels > 0)
    s << "\ndropping specks: " << in.specks.specks << " specks (" << in.specks.pixels
      << " pixels) cleared";
  if (in.gaps.radius_px > 0)
    s << "\nclosing gaps: " << in.gaps.gaps_closed << " gaps closed, " << in.gaps.pixels_filled
      << " pixels filled, " << in.gaps.regions_joined << " occupied regions joined";
  opening_lines(in, s);
  return s.str();  // the warnings go apart, on stderr (RosImport::warnings)
}

}  // namespace plumekit
