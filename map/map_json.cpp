#include "map/map_json.hpp"

#include <cmath>
#include <set>
#include <sstream>
#include <vector>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/option_check.hpp"

namespace plumekit {

using nlohmann::json;

namespace {

// JSON has no NaN or Infinity, but Python's json.dump writes them as bare
// tokens. Quote them so the parser accepts the file and the reader can name
// the exact key that holds the non-finite value.
std::string quote_non_finite_tokens(std::string_view text) {
  static const char* const kTokens[] = {"-Infinity", "Infinity", "NaN"};
  std::string out;
  out.reserve(text.size());
  bool in_string = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      out += c;
      if (c == '\\' && i + 1 < text.size())
        out += text[++i];
      else if (c == '"')
        in_string = false;
      continue;
    }
    if (c == '"') in_string = true;
    bool replaced = false;
    for (const char* token : kTokens) {
      const std::string_view t(token);
      if (text.substr(i, t.size()) == t) {
        out += '"';
        out += t;
        out += '"';
        i += t.size() - 1;
        replaced = true;
        break;
      }
    }
    if (!replaced) out += c;
  }
  return out;
}

// Reads typed values out of parsed JSON, naming the key path in every error.
class Reader {
 public:
  explicit Reader(std::string origin) : origin_(std::move(origin)) {}

  [[noreturn]] void fail(const std::string& key, const std::string& what) const {
    throw InputError(origin_ + ": " + (key.empty() ? "" : key + ": ") + what);
  }

  void only_keys(const json& obj, const std::string& path, std::set<std::string> allowed) const {
    for (const auto& [key, value] : obj.items()) {
      if (allowed.count(key)) continue;
      std::string list;
      for (const std::string& a : allowed)
        list += (list.empty() ? "" : ", ") + a;
      fail(join(path, key), "unknown key (allowed here: " + list + ")");
    }
  }

  const json& object(const json& v, const std::string& path) const {
    if (!v.is_object()) fail(path, std::string("expected an object, found ") + v.type_name());
    return v;
  }

  const json& array(const json& v, const std::string& path) const {
    if (!v.is_array()) fail(path, std::string("expected an array, found ") + v.type_name());
    return v;
  }

  const json& required(const json& obj, const std::string& path, const char* key) const {
    auto it = obj.find(key);
    if (it == obj.end()) fail(join(path, key), "missing (required)");
    return *it;
  }

  double number(const json& v, const std::string& path) const {
    if (v.is_string()) {
      const std::string s = v.get<std::string>();
      if (s == "NaN" || s == "Infinity" || s == "-Infinity")
        fail(path, s + " is not allowed; every number must be finite");
    }
    if (!v.is_number()) fail(path, std::string("expected a number, found ") + v.type_name());
    const double x = v.get<double>();
    if (!std::isfinite(x)) fail(path, "number is not finite");
    return x;
  }

  std::string string(const json& v, const std::string& path) const {
    if (!v.is_string()) fail(path, std::string("expected a string, found ") + v.type_name());
    return v.get<std::string>();
  }

  Vec2 point(const json& v, const std::string& path) const {
    array(v, path);
    if (v.size() != 2)
      fail(path, "expected a point [x, y], found " + std::to_string(v.size()) + " numbers");
    return {number(v[0], index(path, 0)), number(v[1], index(path, 1))};
  }

  static std::string join(const std::string& path, const std::string& key) {
    return path.empty() ? key : path + "." + key;
  }
  static std::string index(const std::string& path, std::size_t i) {
    return path + "[" + std::to_string(i) + "]";
  }

 private:
  std::string origin_;
};

Side parse_side(const Reader& r, const json& v, const std::string& path) {
  const std::string s = r.string(v, path);
  if (s == "left") return Side::Left;
  if (s == "right") return Side::Right;
  if (s == "bottom") return Side::Bottom;
  if (s == "top") return Side::Top;
  r.fail(path, "'" + s + "' is not a side; use left, right, bottom or top");
}

Profile parse_profile(const Reader& r, const json& v, const std::string& path) {
  const std::string p = r.string(v, path);
  if (p == "uniform") return Profile::Uniform;
  if (p == "parabolic") return Profile::Parabolic;
  r.fail(path, "'" + p + "' is not a profile; use uniform or parabolic");
}

// A /1 span, side/from/to along an arena wall (from and to default to the
// whole wall), checked in the wall's own terms.
struct WallSpan {
  Side side = Side::Left;
  double from = 0.0;
  double to = 0.0;
};

WallSpan parse_wall_span(const Reader& r, const json& v, const std::string& path, const Map& map) {
  WallSpan w;
  w.side = parse_side(r, r.required(v, path, "side"), Reader::join(path, "side"));
  w.from = v.contains("from") ? r.number(v["from"], Reader::join(path, "from")) : 0.0;
  w.to = v.contains("to") ? r.number(v["to"], Reader::join(path, "to")) : map.wall_length(w.side);
  const double length = map.wall_length(w.side);
  std::ostringstream s;
  s << "span [" << w.from << ", " << w.to << "] on the " << to_string(w.side) << " wall ";
  if (!(w.from < w.to)) r.fail(path, s.str() + "is empty: 'from' must be less than 'to'");
  if (w.from < 0.0 || w.to > length) {
    std::ostringstream l;
    l << "lies outside the wall, which runs from 0 to " << length << " m";
    r.fail(path, s.str() + l.str());
  }
  return w;
}

// plumekit-map/1: one inlet and one outlet, each a span of an arena wall.
void parse_v1_openings(const Reader& r, const json& doc, Map& map) {
  const json& inlet = r.object(r.required(doc, "", "inlet"), "inlet");
  r.only_keys(inlet, "inlet", {"side", "from", "to", "speed", "profile"});
  const WallSpan in = parse_wall_span(r, inlet, "inlet", map);
  const double speed = r.number(r.required(inlet, "inlet", "speed"), "inlet.speed");
  const Profile profile = inlet.contains("profile")
                              ? parse_profile(r, inlet["profile"], "inlet.profile")
                              : Profile::Uniform;
  const json& outlet = r.object(r.required(doc, "", "outlet"), "outlet");
  r.only_keys(outlet, "outlet", {"side", "from", "to"});
  const WallSpan out = parse_wall_span(r, outlet, "outlet", map);
  if (in.side == out.side && out.from < in.to && in.from < out.to) {
    std::ostringstream s;
    s << "span [" << out.from << ", " << out.to << "] overlaps the inlet's [" << in.from << ", "
      << in.to << "] on the " << to_string(out.side) << " wall";
    r.fail("outlet", s.str());
  }
  map.openings = {wall_opening(map, in.side, in.from, in.to, OpeningKind::Inlet, speed, profile),
                  wall_opening(map, out.side, out.from, out.to, OpeningKind::Outlet)};
}

// The largest frame offset and arena a framed map may have: its file
// coordinates are written to the micrometre, which doubles hold with room to
// spare below this.
constexpr double kMaxFramedExtent = 1e7;
constexpr double kMicrometresPerMetre = 1e6;

// A framed map's file coordinates are micrometres: integer micrometres over
// 1e6, the double nearest the decimal, so "-9.1" reads and writes back as
// "-9.1". Rounded on reading too, so that a map read, written and read again
// is the same map (and is checked as the one written).
double micrometres(double v) {
  return std::round(v * kMicrometresPerMetre) / kMicrometresPerMetre;
}

// A coordinate as a file holds it: in the map frame, to the micrometre when framed.
double file_coordinate(double arena, double origin) {
  if (origin == 0.0) return arena;
  return micrometres(arena + origin);
}

// A point read from a file, in the arena frame.
Vec2 from_file(const Map& map, Vec2 p) {
  if (!map.has_frame()) return p;
  return map.from_frame({micrometres(p.x), micrometres(p.y)});
}

// Snaps a coordinate that lies within round-off of an arena wall onto it, so
// that an opening on a wall written in the map frame is on that wall.
double snap_to_wall(double v, double wall, double slack) {
  if (std::abs(v) <= slack) return 0.0;
  if (std::abs(v - wall) <= slack) return wall;
  return v;
}

// plumekit-map/2: any number of openings, each from/to in the map frame.
void parse_v2_openings(const Reader& r, const json& doc, Map& map) {
  const json& list = r.array(r.required(doc, "", "openings"), "openings");
  const double slack = map.round_off();
  for (std::size_t k = 0; k < list.size(); ++k) {
    const std::string key = Reader::index("openings", k);
    const json& v = r.object(list[k], key);
    const std::string kind = r.string(r.required(v, key, "kind"), Reader::join(key, "kind"));
    Opening o;
    if (kind == "inlet") {
      r.only_keys(v, key, {"kind", "from", "to", "speed", "profile"});
      o.kind = OpeningKind::Inlet;
      o.speed = r.number(r.required(v, key, "speed"), Reader::join(key, "speed"));
      if (v.contains("profile"))
        o.profile = parse_profile(r, v["profile"], Reader::join(key, "profile"));
    } else if (kind == "outlet") {
      r.only_keys(v, key, {"kind", "from", "to"});
      o.kind = OpeningKind::Outlet;
    } else {
      r.fail(Reader::join(key, "kind"), "'" + kind + "' is not an opening; use inlet or outlet");
    }
    o.from = from_file(map, r.point(r.required(v, key, "from"), Reader::join(key, "from")));
    o.to = from_file(map, r.point(r.required(v, key, "to"), Reader::join(key, "to")));
    for (Vec2* p : {&o.from, &o.to})
      *p = {snap_to_wall(p->x, map.width, slack), snap_to_wall(p->y, map.height, slack)};
    map.openings.push_back(o);
  }
}

void parse_frame(const Reader& r, const json& doc, Map& map) {
  if (!doc.contains("frame")) return;
  const json& frame = r.object(doc["frame"], "frame");
  r.only_keys(frame, "frame", {"origin"});
  // Rounded like every other coordinate, so that the arena's edges, written as
  // micrometres, read back on the arena's edges (and files that an earlier
  // plumekit wrote with an unrounded origin read too).
  const Vec2 origin = r.point(r.required(frame, "frame", "origin"), "frame.origin");
  map.frame.origin = file_origin(origin);
}

void parse_shapes(const Reader& r, const json& doc, Map& map) {
  if (doc.contains("obstacles")) {
    const json& obstacles = r.array(doc["obstacles"], "obstacles");
    for (std::size_t k = 0; k < obstacles.size(); ++k) {
      const std::string key = Reader::index("obstacles", k);
      const json& poly = r.array(obstacles[k], key);
      if (poly.size() < 3)
        r.fail(key,
               "polygon has " + std::to_string(poly.size()) + " vertices; it needs at least 3");
      Polygon p;
      for (std::size_t v = 0; v < poly.size(); ++v)
        p.push_back(from_file(map, r.point(poly[v], Reader::index(key, v))));
      map.obstacles.push_back(std::move(p));
    }
  }
  // Sources and starts: lists of points, each read the same way.
  for (const auto& [key, list] : {std::pair{"sources", &map.sources}, {"starts", &map.starts}}) {
    if (!doc.contains(key)) continue;
    const json& points = r.array(doc[key], key);
    for (std::size_t k = 0; k < points.size(); ++k)
      list->push_back(from_file(map, r.point(points[k], Reader::index(key, k))));
  }
}

using ordered_json = nlohmann::ordered_json;

ordered_json json_point(const Map& map, Vec2 p) {
  return ordered_json::array(
      {file_coordinate(p.x, map.frame.origin.x), file_coordinate(p.y, map.frame.origin.y)});
}

// What a message calls opening k: "inlet"/"outlet" in a /1 map, else "openings[k]".
std::string opening_key(const Map& map, std::size_t k) {
  if (map.format_version == 1 && map.openings.size() == 2) return k == 0 ? "inlet" : "outlet";
  return Reader::index("openings", k);
}

std::string framed(const Map& map, Vec2 p) {
  return to_string(map.to_frame(p));
}

// The positions along opening o where some obstacle edge meets its line: the
// only places where what lies beside it can change.
std::vector<double> boundary_events(const Map& map, const Opening& o, double slack) {
  std::vector<double> at{o.lo(), o.hi()};
  const bool vertical = o.vertical();
  auto across = [&](Vec2 p) { return vertical ? p.x : p.y; };
  auto along = [&](Vec2 p) { return vertical ? p.y : p.x; };
  for (const Polygon& poly : map.obstacles) {
    for (std::size_t i = 0; i < poly.size(); ++i) {
      const Vec2 p = poly[i], q = poly[(i + 1) % poly.size()];
      const double dp = across(p) - o.line(), dq = across(q) - o.line();
      if (std::abs(dp) <= slack) at.push_back(along(p));
      if (std::abs(dq) <= slack) at.push_back(along(q));
      if ((dp < -slack && dq > slack) || (dp > slack && dq < -slack))
        at.push_back(along(p) + (along(q) - along(p)) * dp / (dp - dq));
    }
  }
  std::sort(at.begin(), at.end());
  std::vector<double> inside;
  for (double s : at)
    if (s >= o.lo() && s <= o.hi()) inside.push_back(s);
  return inside;
}

// Why opening o is not on the boundary of the free space (free space on one
// side of it all along, an obstacle or the outside on the other), or "".
std::string boundary_fault(const Map& map, const Opening& o) {
  const double slack = map.round_off();
  const double probe = map.probe_distance();
  const Vec2 normal = o.vertical() ? Vec2{1.0, 0.0} : Vec2{0.0, 1.0};
  const std::vector<double> events = boundary_events(map, o, slack);
  int free_side = 0;
  for (std::size_t e = 0; e + 1 < events.size(); ++e) {
    if (events[e + 1] - events[e] <= slack) continue;
    const double mid = 0.5 * (events[e] + events[e + 1]);
    const Vec2 at = o.vertical() ? Vec2{o.line(), mid} : Vec2{mid, o.line()};
    const bool plus = map.is_free(at + probe * normal);
    const bool minus = map.is_free(at - probe * normal);
    if (plus && minus)
      return "at " + framed(map, at) +
             " it crosses free space; an opening lies on an arena wall or an obstacle's edge";
    if (!plus && !minus) {
      // Blocked here (an obstacle against it), which is allowed on an arena
      // wall or an obstacle's edge, not inside an obstacle.
      if (map.wall_of(o)) continue;
      bool on_edge = false;
      for (const Polygon& poly : map.obstacles)
        on_edge = on_edge || locate(poly, at) == Location::Boundary;
      if (!on_edge) return "at " + framed(map, at) + " it lies inside an obstacle";
      continue;
    }
    const int side = plus ? 1 : -1;
    if (free_side != 0 && side != free_side)
      return "its free side changes at " + framed(map, at) + "; split it into two openings";
    free_side = side;
  }
  return "";
}

void validate_opening(const Reader& r, const Map& map, std::size_t k) {
  const Opening& o = map.openings[k];
  const std::string key = opening_key(map, k);
  if (!is_finite(o.from) || !is_finite(o.to)) r.fail(key, "an end is not finite");
  if (o.from.x != o.to.x && o.from.y != o.to.y)
    r.fail(key, "from " + framed(map, o.from) + " to " + framed(map, o.to) +
                    " is not parallel to an axis; openings run along x or along y");
  if (o.from == o.to) r.fail(key, "from and to are the same point " + framed(map, o.from));
  for (Vec2 p : {o.from, o.to})
    if (!map.in_arena(p)) r.fail(key, "end " + framed(map, p) + " lies outside the arena");
  if (o.is_inlet() && !(std::isfinite(o.speed) && o.speed > 0.0))
    r.fail(Reader::join(key, "speed"), "must be a positive, finite speed in m/s");
  if (o.is_inlet() && o.speed > kMaxInletSpeed)
    r.fail(Reader::join(key, "speed"),
           compact(o.speed) + " m/s is too fast; an inlet blows " + kInletSpeedBound);
  if (const std::string fault = boundary_fault(map, o); !fault.empty())
    r.fail(key, "not on the boundary of the free space: " + fault);
}

void validate_openings(const Reader& r, const Map& map) {
  if (map.format_version == 1) {
    if (map.openings.size() != 2 || !map.openings[0].is_inlet() || map.openings[1].is_inlet() ||
        !map.wall_of(map.openings[0]) || !map.wall_of(map.openings[1]) || map.has_frame())
      r.fail("format", "plumekit-map/1 holds one inlet and one outlet on the arena's walls and " +
                           std::string("no frame; write this map as plumekit-map/2"));
  }
  bool inlet = false, outlet = false;
  for (std::size_t k = 0; k < map.openings.size(); ++k) {
    validate_opening(r, map, k);
    (map.openings[k].is_inlet() ? inlet : outlet) = true;
  }
  if (!inlet || !outlet)
    r.fail("openings", "a map needs at least one inlet and one outlet, found " +
                           std::string(inlet    ? "no outlet"
                                       : outlet ? "no inlet"
                                                : "neither"));
  const double slack = map.round_off();
  for (std::size_t k = 0; k < map.openings.size(); ++k) {
    const Opening& a = map.openings[k];
    for (std::size_t i = 0; i < k; ++i) {
      const Opening& b = map.openings[i];
      if (a.vertical() != b.vertical() || std::abs(a.line() - b.line()) > slack) continue;
      if (std::min(a.hi(), b.hi()) - std::max(a.lo(), b.lo()) <= slack) continue;
      r.fail(opening_key(map, k),
             "overlaps " + opening_key(map, i) +
                 (a.kind != b.kind ? ": an inlet and an outlet cannot share a stretch" : ""));
    }
  }
}

void validate_frame(const Reader& r, const Map& map) {
  if (!map.has_frame()) return;
  const Vec2 o = map.frame.origin;
  if (!is_finite(o)) r.fail("frame.origin", "is not finite");
  if (std::max({std::abs(o.x), std::abs(o.y), map.width, map.height}) > kMaxFramedExtent)
    r.fail("frame.origin", "a framed map's origin and size must be within 1e7 m");
}

}  // namespace

void validate_map(const Map& map, const std::string& origin) {
  const Reader r(origin);
  if (!(std::isfinite(map.width) && map.width > 0 && std::isfinite(map.height) && map.height > 0)) {
    std::ostringstream s;
    s << "arena must be a positive, finite width and height, found [" << map.width << ", "
      << map.height << "]";
    r.fail("size", s.str());
  }
  validate_frame(r, map);

  // Vertices may touch the walls; allow for round-off in files written by other tools.
  const double slack = 1e-9 * std::max(map.width, map.height);
  for (std::size_t k = 0; k < map.obstacles.size(); ++k) {
    const Polygon& poly = map.obstacles[k];
    const std::string key = Reader::index("obstacles", k);
    for (std::size_t v = 0; v < poly.size(); ++v) {
      const Vec2 p = poly[v];
      if (!is_finite(p)) r.fail(Reader::index(key, v), "vertex is not finite");
      if (p.x < -slack || p.x > map.width + slack || p.y < -slack || p.y > map.height + slack) {
        std::ostringstream s;
        s << "vertex " << framed(map, p) << " lies outside the " << map.width << " x " << map.height
          << " m arena";
        r.fail(Reader::index(key, v), s.str());
      }
    }
    if (auto fault = simplicity_fault(poly)) r.fail(key, "polygon is not simple: " + *fault);
  }
  validate_openings(r, map);
  // Sources and starts: finite points in the arena's free space.
  for (const auto& [list, noun] :
       {std::pair<const std::vector<Vec2>*, std::string>{&map.sources, "source"},
        {&map.starts, "start"}}) {
    for (std::size_t k = 0; k < list->size(); ++k) {
      const Vec2 p = (*list)[k];
      const std::string key = Reader::index(noun + "s", k);
      if (!is_finite(p)) r.fail(key, noun + " is not finite");
      if (!map.in_arena(p)) r.fail(key, noun + " " + framed(map, p) + " lies outside the arena");
      if (const int o = map.obstacle_at(p); o >= 0)
        r.fail(key,
               noun + " " + framed(map, p) + " lies inside obstacles[" + std::to_string(o) + "]");
    }
  }
  if (map.format_version == 1 && !map.starts.empty())
    r.fail("starts", "plumekit-map/1 has no starts; write the map as plumekit-map/2");
}

namespace {

json parse_json(std::string_view text, const Reader& r) {
  const std::string quoted = quote_non_finite_tokens(text);
  // nlohmann keeps the last of two equal keys; a map file with one is a typo.
  std::vector<std::set<std::string>> seen;
  auto reject_duplicates = [&](int, json::parse_event_t event, json& parsed) {
    if (event == json::parse_event_t::object_start) seen.emplace_back();
    if (event == json::parse_event_t::object_end) seen.pop_back();
    if (event == json::parse_event_t::key && !seen.back().insert(parsed.get<std::string>()).second)
      r.fail(parsed.get<std::string>(), "key appears twice in the same object");
    return true;
  };
  try {
    return json::parse(quoted, reject_duplicates);
  } catch (const json::exception& e) {  // syntax, or a number too large for a double
    // Drop nlohmann's "[json.exception.parse_error.101] " prefix; keep line and column.
    const std::string what = e.what();
    const std::size_t end = what.find("] ");
    r.fail("", "not valid JSON: " + (end == std::string::npos ? what : what.substr(end + 2)));
  }
}

}  // namespace

Vec2 file_origin(Vec2 origin) {
  // One too far out to be framed stays as given, for validate_frame to refuse.
  auto round = [](double v) { return std::abs(v) <= kMaxFramedExtent ? micrometres(v) : v; };
  return {round(origin.x), round(origin.y)};
}

Map parse_map(std::string_view text, const std::string& origin) {
  const Reader r(origin);
  const json doc = parse_json(text, r);
  r.object(doc, "");
  const std::string format = r.string(r.required(doc, "", "format"), "format");
  Map map;
  if (format == kMapFormatV1) {
    map.format_version = 1;
    r.only_keys(
        doc, "",
        {"format", "name", "generated_by", "size", "inlet", "outlet", "obstacles", "sources"});
  } else if (format == kMapFormat) {
    r.only_keys(doc, "",
                {"format", "name", "generated_by", "frame", "size", "openings", "obstacles",
                 "sources", "starts"});
  } else {
    r.fail("format", "'" + format + "' is not supported; this plumekit reads " + kMapFormat +
                         " and " + kMapFormatV1);
  }
  if (doc.contains("name")) map.name = r.string(doc["name"], "name");
  if (doc.contains("generated_by"))
    map.generated_by = r.string(doc["generated_by"], "generated_by");
  const Vec2 size = r.point(r.required(doc, "", "size"), "size");
  map.width = size.x;
  map.height = size.y;
  if (!(map.width > 0 && map.height > 0)) r.fail("size", "width and height must be positive");
  if (map.format_version == 1) {
    parse_v1_openings(r, doc, map);
  } else {
    parse_frame(r, doc, map);
    validate_frame(r, map);
    parse_v2_openings(r, doc, map);
  }
  parse_shapes(r, doc, map);
  validate_map(map, origin);
  return map;
}

Map read_map(const std::filesystem::path& path) {
  return parse_map(read_file(path), path.string());
}

namespace {

void add_v1_openings(const Map& map, ordered_json& j) {
  const Opening& in = map.openings[0];
  const Opening& out = map.openings[1];
  j["inlet"] = {{"side", to_string(*map.wall_of(in))},
                {"from", in.lo()},
                {"to", in.hi()},
                {"speed", in.speed},
                {"profile", to_string(in.profile)}};
  j["outlet"] = {{"side", to_string(*map.wall_of(out))}, {"from", out.lo()}, {"to", out.hi()}};
}

void add_v2_openings(const Map& map, ordered_json& j) {
  if (map.has_frame()) {
    const Vec2 origin = file_origin(map.frame.origin);
    j["frame"] = {{"origin", ordered_json::array({origin.x, origin.y})}};
  }
  j["size"] = {map.width, map.height};
  j["openings"] = ordered_json::array();
  for (const Opening& o : map.openings) {
    ordered_json v{{"kind", to_string(o.kind)},
                   {"from", json_point(map, o.from)},
                   {"to", json_point(map, o.to)}};
    if (o.is_inlet()) {
      v["speed"] = o.speed;
      v["profile"] = to_string(o.profile);
    }
    j["openings"].push_back(std::move(v));
  }
}

}  // namespace

nlohmann::ordered_json map_to_json(const Map& map) {
  ordered_json j;
  j["format"] = map.format_version == 1 ? kMapFormatV1 : kMapFormat;
  j["name"] = map.name;
  if (!map.generated_by.empty()) j["generated_by"] = map.generated_by;
  if (map.format_version == 1) {
    j["size"] = {map.width, map.height};
    add_v1_openings(map, j);
  } else {
    add_v2_openings(map, j);
  }
  j["obstacles"] = ordered_json::array();
  for (const Polygon& poly : map.obstacles) {
    ordered_json p = ordered_json::array();
    for (Vec2 v : poly)
      p.push_back(json_point(map, v));
    j["obstacles"].push_back(std::move(p));
  }
  j["sources"] = ordered_json::array();
  for (Vec2 s : map.sources)
    j["sources"].push_back(json_point(map, s));
  // Only when there are any, so that a map without starts keeps its bytes.
  if (!map.starts.empty()) {
    j["starts"] = ordered_json::array();
    for (Vec2 s : map.starts)
      j["starts"].push_back(json_point(map, s));
  }
  return j;
}

std::string map_file_text(const Map& map, const std::string& origin) {
  validate_map(map, origin);
  // Hand-laid so that a file stays readable: one line per key, opening, polygon or source.
  const ordered_json j = map_to_json(map);
  std::ostringstream out;
  out << "{\n";
  const char* const order[] = {"format", "name",  "generated_by", "frame",
                               "size",   "inlet", "outlet"};
  for (const char* key : order)
    if (j.contains(key)) out << "  \"" << key << "\": " << j[key].dump() << ",\n";
  const std::string last = j.contains("starts") ? "starts" : "sources";
  for (const char* key : {"openings", "obstacles", "sources", "starts"}) {
    if (!j.contains(key)) continue;
    out << "  \"" << key << "\": [";
    const ordered_json& list = j[key];
    for (std::size_t i = 0; i < list.size(); ++i)
      out << (i ? ",\n    " : "\n    ") << list[i].dump();
    out << (list.empty() ? "]" : "\n  ]") << (key != last ? ",\n" : "\n");
  }
  out << "}\n";
  return out.str();
}

void write_map(const Map& map, const std::filesystem::path& path) {
  write_file_atomic(path, map_file_text(map, path.string()));
}

}  // namespace plumekit
