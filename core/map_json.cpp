#include "core/map_json.hpp"

#include <cmath>
#include <set>
#include <sstream>
#include <vector>

#include "core/atomic_file.hpp"
#include "core/error.hpp"

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

// Reads side/from/to; from and to default to the whole wall.
void parse_opening(const Reader& r, const json& v, const std::string& path, const Map& map,
                   Opening& o) {
  o.side = parse_side(r, r.required(v, path, "side"), Reader::join(path, "side"));
  o.from = v.contains("from") ? r.number(v["from"], Reader::join(path, "from")) : 0.0;
  o.to = v.contains("to") ? r.number(v["to"], Reader::join(path, "to")) : map.wall_length(o.side);
}

using ordered_json = nlohmann::ordered_json;

ordered_json json_point(Vec2 p) {
  return ordered_json::array({p.x, p.y});
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
  auto check_span = [&](const Opening& o, const std::string& key) {
    const double length = map.wall_length(o.side);
    std::ostringstream s;
    s << "span [" << o.from << ", " << o.to << "] on the " << to_string(o.side) << " wall ";
    if (!std::isfinite(o.from) || !std::isfinite(o.to)) r.fail(key, s.str() + "is not finite");
    if (!(o.from < o.to)) r.fail(key, s.str() + "is empty: 'from' must be less than 'to'");
    if (o.from < 0.0 || o.to > length) {
      std::ostringstream l;
      l << "lies outside the wall, which runs from 0 to " << length << " m";
      r.fail(key, s.str() + l.str());
    }
  };
  check_span(map.inlet, "inlet");
  check_span(map.outlet, "outlet");
  if (!(std::isfinite(map.inlet.speed) && map.inlet.speed > 0.0))
    r.fail("inlet.speed", "must be a positive, finite speed in m/s");
  if (map.inlet.side == map.outlet.side && map.outlet.from < map.inlet.to &&
      map.inlet.from < map.outlet.to) {
    std::ostringstream s;
    s << "span [" << map.outlet.from << ", " << map.outlet.to << "] overlaps the inlet's ["
      << map.inlet.from << ", " << map.inlet.to << "] on the " << to_string(map.outlet.side)
      << " wall";
    r.fail("outlet", s.str());
  }

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
        s << "vertex " << to_string(p) << " lies outside the " << map.width << " x " << map.height
          << " m arena";
        r.fail(Reader::index(key, v), s.str());
      }
    }
    if (auto fault = simplicity_fault(poly)) r.fail(key, "polygon is not simple: " + *fault);
  }
  for (std::size_t k = 0; k < map.sources.size(); ++k) {
    const Vec2 p = map.sources[k];
    const std::string key = Reader::index("sources", k);
    if (!is_finite(p)) r.fail(key, "source is not finite");
    if (!map.in_arena(p)) r.fail(key, "source " + to_string(p) + " lies outside the arena");
    if (const int o = map.obstacle_at(p); o >= 0)
      r.fail(key, "source " + to_string(p) + " lies inside obstacles[" + std::to_string(o) + "]");
  }
}

Map parse_map(std::string_view text, const std::string& origin) {
  const Reader r(origin);
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
  json doc;
  try {
    doc = json::parse(quoted, reject_duplicates);
  } catch (const json::exception& e) {  // syntax, or a number too large for a double
    // Drop nlohmann's "[json.exception.parse_error.101] " prefix; keep line and column.
    const std::string what = e.what();
    const std::size_t end = what.find("] ");
    r.fail("", "not valid JSON: " + (end == std::string::npos ? what : what.substr(end + 2)));
  }

  r.object(doc, "");
  r.only_keys(doc, "",
              {"format", "name", "generated_by", "size", "inlet", "outlet", "obstacles", "sources"});
  const std::string format = r.string(r.required(doc, "", "format"), "format");
  if (format != kMapFormat)
    r.fail("format", "'" + format + "' is not supported; this plumekit reads " + kMapFormat);

  Map map;
  if (doc.contains("name")) map.name = r.string(doc["name"], "name");
  if (doc.contains("generated_by")) map.generated_by = r.string(doc["generated_by"], "generated_by");
  const Vec2 size = r.point(r.required(doc, "", "size"), "size");
  map.width = size.x;
  map.height = size.y;
  if (!(map.width > 0 && map.height > 0)) r.fail("size", "width and height must be positive");

  const json& inlet = r.object(r.required(doc, "", "inlet"), "inlet");
  r.only_keys(inlet, "inlet", {"side", "from", "to", "speed", "profile"});
  parse_opening(r, inlet, "inlet", map, map.inlet);
  map.inlet.speed = r.number(r.required(inlet, "inlet", "speed"), "inlet.speed");
  if (inlet.contains("profile")) {
    const std::string p = r.string(inlet["profile"], "inlet.profile");
    if (p == "uniform")
      map.inlet.profile = Profile::Uniform;
    else if (p == "parabolic")
      map.inlet.profile = Profile::Parabolic;
    else
      r.fail("inlet.profile", "'" + p + "' is not a profile; use uniform or parabolic");
  }

  const json& outlet = r.object(r.required(doc, "", "outlet"), "outlet");
  r.only_keys(outlet, "outlet", {"side", "from", "to"});
  parse_opening(r, outlet, "outlet", map, map.outlet);

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
        p.push_back(r.point(poly[v], Reader::index(key, v)));
      map.obstacles.push_back(std::move(p));
    }
  }
  if (doc.contains("sources")) {
    const json& sources = r.array(doc["sources"], "sources");
    for (std::size_t k = 0; k < sources.size(); ++k)
      map.sources.push_back(r.point(sources[k], Reader::index("sources", k)));
  }
  validate_map(map, origin);
  return map;
}

Map read_map(const std::filesystem::path& path) {
  return parse_map(read_file(path), path.string());
}

nlohmann::ordered_json map_to_json(const Map& map) {
  ordered_json j;
  j["format"] = kMapFormat;
  j["name"] = map.name;
  if (!map.generated_by.empty()) j["generated_by"] = map.generated_by;
  j["size"] = {map.width, map.height};
  j["inlet"] = {{"side", to_string(map.inlet.side)},
                {"from", map.inlet.from},
                {"to", map.inlet.to},
                {"speed", map.inlet.speed},
                {"profile", to_string(map.inlet.profile)}};
  j["outlet"] = {
      {"side", to_string(map.outlet.side)}, {"from", map.outlet.from}, {"to", map.outlet.to}};
  j["obstacles"] = ordered_json::array();
  for (const Polygon& poly : map.obstacles) {
    ordered_json p = ordered_json::array();
    for (Vec2 v : poly)
      p.push_back(json_point(v));
    j["obstacles"].push_back(std::move(p));
  }
  j["sources"] = ordered_json::array();
  for (Vec2 s : map.sources)
    j["sources"].push_back(json_point(s));
  return j;
}

std::string map_file_text(const Map& map, const std::string& origin) {
  validate_map(map, origin);
  // Hand-laid so that a file stays readable: one line per key, polygon or source.
  const ordered_json j = map_to_json(map);
  std::ostringstream out;
  out << "{\n";
  const char* const order[] = {"format", "name", "generated_by", "size", "inlet", "outlet"};
  for (const char* key : order)
    if (j.contains(key)) out << "  \"" << key << "\": " << j[key].dump() << ",\n";
  for (const char* key : {"obstacles", "sources"}) {
    out << "  \"" << key << "\": [";
    const ordered_json& list = j[key];
    for (std::size_t i = 0; i < list.size(); ++i)
      out << (i ? ",\n    " : "\n    ") << list[i].dump();
    out << (list.empty() ? "]" : "\n  ]") << (std::string(key) == "obstacles" ? ",\n" : "\n");
  }
  out << "}\n";
  return out.str();
}

void write_map(const Map& map, const std::filesystem::path& path) {
  write_file_atomic(path, map_file_text(map, path.string()));
}

}  // namespace plumekit
