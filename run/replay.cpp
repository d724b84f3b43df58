#include "run/replay.hpp"

#include <algorithm>
#include <cmath>

#include <nlohmann/json.hpp>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/image_io.hpp"
#include "core/output_target.hpp"
#include "core/sha256.hpp"
#include "map/map_json.hpp"

namespace plumekit::run {

namespace fs = std::filesystem;
using nlohmann::json;
using nlohmann::ordered_json;

double Replay::plume_concentration(std::uint8_t level) const {
  const double span = std::log1p(plume_top / kReplayPlumeFloor);
  return kReplayPlumeFloor * std::expm1(span * level / 255.0);
}

std::uint8_t Replay::plume_level(double c) const {
  if (!(c > 0.0)) return 0;
  const double span = std::log1p(plume_top / kReplayPlumeFloor);
  const double level = 255.0 * std::log1p(std::min(c, plume_top) / kReplayPlumeFloor) / span;
  return static_cast<std::uint8_t>(std::clamp(std::lround(level), 0L, 255L));
}

namespace {

// Points in the map's frame (its file's coordinates), as run.json has them.
ordered_json point(const Map& map, Vec2 arena) {
  const Vec2 p = map.to_frame(arena);
  return ordered_json::array({p.x, p.y});
}

ordered_json grid_json(const GridShape& g) {
  return {{"nx", g.nx}, {"ny", g.ny}, {"width", g.width}, {"height", g.height}};
}

// The grids' film strip: frame after frame, each with the arena's top row first.
cv::Mat film_strip(const std::vector<std::uint8_t>& cells, const GridShape& g) {
  const int frames = g.size() == 0 ? 0 : static_cast<int>(cells.size() / g.size());
  cv::Mat strip(std::max(1, frames * g.ny), std::max(1, g.nx), CV_8UC1, cv::Scalar(0));
  for (int f = 0; f < frames; ++f)
    for (int j = 0; j < g.ny; ++j)
      std::copy_n(cells.data() + f * g.size() + g.index(0, j), g.nx,
                  strip.ptr<std::uint8_t>(f * g.ny + (g.ny - 1 - j)));
  return strip;
}

std::vector<std::uint8_t> cells_of(const cv::Mat& strip, const GridShape& g, int frames) {
  std::vector<std::uint8_t> cells(static_cast<std::size_t>(frames) * g.size());
  for (int f = 0; f < frames; ++f)
    for (int j = 0; j < g.ny; ++j)
      std::copy_n(strip.ptr<std::uint8_t>(f * g.ny + (g.ny - 1 - j)), g.nx,
                  cells.data() + f * g.size() + g.index(0, j));
  return cells;
}

// Writes `bytes` and reads them back.
void write_checked(const fs::path& file, const std::string& bytes) {
  write_file_atomic(file, bytes);
  if (read_file(file) != bytes)
    throw std::runtime_error(file.string() + ": read back other bytes than were written");
}

// A tunnel replay's view from the side, and its two strips' bytes.
ordered_json side_json(const ReplaySide& s, std::string& plume, std::string& belief) {
  plume = mark_png(encode_png(film_strip(s.plume, s.plume_grid)));
  belief = mark_png(encode_png(film_strip(s.belief_cells, s.belief_grid)));
  return {{"height", s.height},
          {"plane_y", s.plane_y},
          {"plane_z", s.plane_z},
          {"plume",
           {{"file", kReplayPlumeSideFile},
            {"grid", grid_json(s.plume_grid)},
            {"sha256", sha256_hex(plume)}}},
          {"belief",
           {{"file", kReplayBeliefSideFile},
            {"grid", grid_json(s.belief_grid)},
            {"peaks", s.belief_peaks},
            {"sha256", sha256_hex(belief)}}}};
}

}  // namespace

namespace {

// A point of the replay in the map's frame; a tunnel replay's carry their height.
ordered_json replay_point(const Replay& r, Vec2 p, double z) {
  ordered_json q = point(r.map, p);
  if (r.side) q.push_back(z);
  return q;
}

// The stops, the readings on the way and the end.
void add_events(const Replay& r, ordered_json& j) {
  const auto at = [&](Vec2 p, double z) { return replay_point(r, p, z); };
  ordered_json stops = ordered_json::array();
  for (const ReplayStop& s : r.stops)
    stops.push_back({{"robot", s.robot},
                     {"position", at(s.position, s.z)},
                     {"arrived_s", s.arrived_s},
                     {"time_s", s.time_s},
                     {"value", s.value},
                     {"estimate", at(s.estimate, s.estimate_z)}});
  j["stops"] = stops;
  ordered_json readings = ordered_json::array();
  for (const ReplayReading& s : r.readings)
    readings.push_back({s.robot, s.time_s, at(s.position, s.z), s.value});
  j["readings"] = {{"columns", {"robot", "time_s", "position", "value"}}, {"rows", readings}};
  j["has_estimate"] = r.has_estimate;
  const double estimate_z = r.side ? r.side->estimate_z : 0.0;
  j["estimate"] = at(r.estimate, estimate_z);
  j["declared_s"] = r.declared_s;
  j["ended_s"] = r.ended_s;
  j["stopped_by"] = r.stopped_by;
  ordered_json approach = ordered_json::array();
  for (Vec2 p : r.approach)  // (a tunnel run has none)
    approach.push_back(at(p, estimate_z));
  j["approach"] = approach;
}

}  // namespace

std::string write_replay(const Replay& r, const fs::path& dir) {
  ordered_json j{{"format", kReplayFormat}, {"generated_by", "plumekit"}, {"title", r.title}};
  j["map"] = map_to_json(r.map);
  j["source"] = replay_point(r, r.source, r.side ? r.side->source_z : 0.0);
  j["method"] = r.method;
  j["robots"] = r.robots;
  j["every_s"] = r.every_s;
  ordered_json frames = ordered_json::array();
  for (std::size_t f = 0; f < r.positions.size(); ++f) {
    ordered_json robots = ordered_json::array();
    for (std::size_t k = 0; k < r.positions[f].size(); ++k)
      robots.push_back(replay_point(r, r.positions[f][k], r.side ? r.side->z.at(f).at(k) : 0.0));
    frames.push_back(robots);
  }
  j["positions"] = frames;
  const std::string plume = mark_png(encode_png(film_strip(r.plume, r.plume_grid)));
  const std::string belief = mark_png(encode_png(film_strip(r.belief_cells, r.belief_grid)));
  j["plume"] = {{"file", kReplayPlumeFile},
                {"grid", grid_json(r.plume_grid)},
                {"floor", kReplayPlumeFloor},
                {"top", r.plume_top},
                {"sha256", sha256_hex(plume)}};
  ordered_json beliefs = ordered_json::array();
  for (const ReplayBelief& b : r.beliefs)
    beliefs.push_back({{"robot", b.robot}, {"time_s", b.time_s}, {"peak", b.peak}});
  j["belief"] = {{"file", kReplayBeliefFile},
                 {"grid", grid_json(r.belief_grid)},
                 {"steps", beliefs},
                 {"sha256", sha256_hex(belief)}};
  add_events(r, j);
  std::string side_plume, side_belief;
  if (r.side) j["side"] = side_json(*r.side, side_plume, side_belief);
  write_checked(dir / kReplayPlumeFile, plume);
  write_checked(dir / kReplayBeliefFile, belief);
  if (r.side) {
    write_checked(dir / kReplayPlumeSideFile, side_plume);
    write_checked(dir / kReplayBeliefSideFile, side_belief);
  }
  std::string text = j.dump(1) + "\n";
  write_checked(dir / kReplayFile, text);
  return text;
}

namespace {

// Reads replay.json's fields, naming the file and the field in every error.
class Reader {
 public:
  Reader(fs::path file, const Map* map) : file_(std::move(file)), map_(map) {}
  // A tunnel replay's points are [x, y, z].
  void with_heights() { dims_ = 3; }
  [[noreturn]] void fail(const std::string& field, const std::string& what) const {
    throw InputError(file_.string() + ": " + field + " " + what);
  }
  const json& at(const json& j, const std::string& key, const std::string& where) const {
    if (!j.is_object() || !j.contains(key)) fail(where + key, "is missing");
    return j[key];
  }
  double number(const json& j, const std::string& key, const std::string& where = "") const {
    const json& v = at(j, key, where);
    if (!v.is_number() || !std::isfinite(v.get<double>())) fail(where + key, "is not a number");
    return v.get<double>();
  }
  int count(const json& j, const std::string& key, const std::string& where = "") const {
    const double v = number(j, key, where);
    if (v != std::floor(v) || v < 0 || v > 1e8) fail(where + key, "is not a count");
    return static_cast<int>(v);
  }
  std::string text(const json& j, const std::string& key) const {
    const json& v = at(j, key, "");
    if (!v.is_string()) fail(key, "is not a string");
    return v.get<std::string>();
  }
  Vec2 point(const json& v, const std::string& field, double* z = nullptr) const {
    if (!v.is_array() || v.size() != dims_ ||
        !std::all_of(v.begin(), v.end(), [](const json& c) { return c.is_number(); }))
      fail(field, dims_ == 2 ? "is not a point [x, y]" : "is not a point [x, y, z]");
    if (z) *z = dims_ == 3 ? v[2].get<double>() : 0.0;
    return map_->from_frame({v[0].get<double>(), v[1].get<double>()});
  }
  GridShape grid(const json& j, const std::string& where) const {
    GridShape g;
    g.nx = count(j, "nx", where);
    g.ny = count(j, "ny", where);
    g.width = number(j, "width", where);
    g.height = number(j, "height", where);
    if (g.size() > 50'000'000) fail(where + "nx", "makes too large a grid");
    return g;
  }
  // A film strip of `frames` grids `g`, checked against its SHA-256.
  std::vector<std::uint8_t> strip(const json& part, const std::string& name, const GridShape& g,
                                  int frames) const {
    const fs::path file = file_.parent_path() / text(part, "file");
    const std::string bytes = read_file(file);
    if (sha256_hex(bytes) != text(part, "sha256"))
      throw InputError(file.string() + ": does not match the SHA-256 " + file_.string() +
                       " records for " + name);
    const cv::Mat image = read_gray_image(file);
    if (image.cols != std::max(1, g.nx) || image.rows != std::max(1, frames * g.ny))
      throw InputError(file.string() + ": is not " + std::to_string(frames) + " frames of the " +
                       name + " grid");
    return cells_of(image, g, frames);
  }

 private:
  fs::path file_;
  const Map* map_;
  std::size_t dims_ = 2;
};

// The stops, the readings on the way and the end.
void read_events(const Reader& in, const json& j, Replay& r) {
  // Where a point's height goes, in a tunnel replay.
  const auto height = [&](double& z) -> double* { return r.side ? &z : nullptr; };
  for (const json& s : in.at(j, "stops", "")) {
    ReplayStop stop{in.count(s, "robot", "stops."),      {},
                    in.number(s, "arrived_s", "stops."), in.number(s, "time_s", "stops."),
                    in.number(s, "value", "stops."),     {}};
    stop.position = in.point(in.at(s, "position", "stops."), "stops.position", height(stop.z));
    stop.estimate =
        in.point(in.at(s, "estimate", "stops."), "stops.estimate", height(stop.estimate_z));
    r.stops.push_back(stop);
  }
  for (const json& row : in.at(in.at(j, "readings", ""), "rows", "readings.")) {
    if (!row.is_array() || row.size() != 4 || !row[0].is_number_integer() || !row[1].is_number() ||
        !row[3].is_number())
      in.fail("readings.rows", "holds a row that is not [robot, time_s, point, value]");
    ReplayReading reading{row[0].get<int>(), {}, row[1].get<double>(), row[3].get<double>()};
    reading.position = in.point(row[2], "readings.rows", height(reading.z));
    r.readings.push_back(reading);
  }
  const json& has = in.at(j, "has_estimate", "");
  if (!has.is_boolean()) in.fail("has_estimate", "is not true or false");
  r.has_estimate = has.get<bool>();
  double ignored = 0.0;
  r.estimate =
      in.point(in.at(j, "estimate", ""), "estimate", r.side ? &r.side->estimate_z : nullptr);
  r.declared_s = in.number(j, "declared_s");
  r.ended_s = in.number(j, "ended_s");
  r.stopped_by = in.text(j, "stopped_by");
  for (const json& p : in.at(j, "approach", ""))
    r.approach.push_back(in.point(p, "approach", &ignored));
  for (const ReplayStop& s : r.stops)
    if (s.robot >= r.robots) in.fail("stops.robot", "names a robot the replay does not have");
  for (const ReplayReading& s : r.readings)
    if (s.robot < 0 || s.robot >= r.robots)
      in.fail("readings.rows", "names a robot the replay does not have");
  for (const ReplayBelief& b : r.beliefs)
    if (b.robot >= r.robots)
      in.fail("belief.steps.robot", "names a robot the replay does not have");
}

// A tunnel replay's view from the side (its plume and belief strips; the heights come with the
// points).
void read_side(const Reader& in, const json& j, Replay& r) {
  ReplaySide& s = *r.side;
  s.height = in.number(j, "height", "side.");
  s.plane_y = in.number(j, "plane_y", "side.");
  s.plane_z = in.number(j, "plane_z", "side.");
  const json& plume = in.at(j, "plume", "side.");
  s.plume_grid = in.grid(in.at(plume, "grid", "side.plume."), "side.plume.grid.");
  s.plume = in.strip(plume, "the side's plume", s.plume_grid, r.frames());
  const json& belief = in.at(j, "belief", "side.");
  s.belief_grid = in.grid(in.at(belief, "grid", "side.belief."), "side.belief.grid.");
  const json& peaks = in.at(belief, "peaks", "side.belief.");
  if (!peaks.is_array() || peaks.size() != r.beliefs.size())
    in.fail("side.belief.peaks", "does not hold a peak per belief step");
  for (const json& p : peaks) {
    if (!p.is_number()) in.fail("side.belief.peaks", "holds a peak that is not a number");
    s.belief_peaks.push_back(p.get<double>());
  }
  s.belief_cells =
      in.strip(belief, "the side's belief", s.belief_grid, static_cast<int>(r.beliefs.size()));
}

}  // namespace

Replay read_replay(const fs::path& dir) {
  const fs::path file = dir / kReplayFile;
  if (!fs::is_regular_file(file))
    throw InputError(dir.string() + ": holds no " + kReplayFile +
                     " (a run records its replay with localize --animate or evaluate --replays)");
  json j;
  try {
    j = json::parse(read_file(file));
  } catch (const json::parse_error& e) {
    throw InputError(file.string() + ": is not JSON (" + e.what() + ")");
  }
  Replay r;
  Reader in(file, &r.map);
  if (in.text(j, "format") != kReplayFormat)
    in.fail("format", "is not " + std::string(kReplayFormat));
  if (j.contains("side")) {
    r.side.emplace();
    in.with_heights();
  }
  r.title = in.text(j, "title");
  r.map = parse_map(in.at(j, "map", "").dump(), file.string() + " (its map)");
  r.source = in.point(in.at(j, "source", ""), "source", r.side ? &r.side->source_z : nullptr);
  r.method = in.text(j, "method");
  r.robots = in.count(j, "robots");
  r.every_s = in.number(j, "every_s");
  if (r.robots < 1 || !(r.every_s > 0.0)) in.fail("robots", "or every_s is not positive");
  for (const json& at : in.at(j, "positions", "")) {
    if (!at.is_array() || static_cast<int>(at.size()) != r.robots)
      in.fail("positions", "holds a frame without a point per robot");
    std::vector<Vec2> frame;
    std::vector<double> heights;
    for (const json& p : at) {
      double z = 0.0;
      frame.push_back(in.point(p, "positions", &z));
      heights.push_back(z);
    }
    r.positions.push_back(std::move(frame));
    if (r.side) r.side->z.push_back(std::move(heights));
  }
  if (r.positions.empty()) in.fail("positions", "holds no frame");
  const json& plume = in.at(j, "plume", "");
  r.plume_grid = in.grid(in.at(plume, "grid", "plume."), "plume.grid.");
  r.plume_top = in.number(plume, "top", "plume.");
  r.plume = in.strip(plume, "the plume", r.plume_grid, r.frames());
  const json& belief = in.at(j, "belief", "");
  r.belief_grid = in.grid(in.at(belief, "grid", "belief."), "belief.grid.");
  for (const json& b : in.at(belief, "steps", "belief."))
    r.beliefs.push_back({in.count(b, "robot", "belief.steps."),
                         in.number(b, "time_s", "belief.steps."),
                         in.number(b, "peak", "belief.steps.")});
  r.belief_cells =
      in.strip(belief, "the belief", r.belief_grid, static_cast<int>(r.beliefs.size()));
  if (r.side) read_side(in, j["side"], r);
  read_events(in, j, r);
  return r;
}

}  // namespace plumekit::run
