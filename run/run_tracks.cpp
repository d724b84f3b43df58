#include "run/run_tracks.hpp"

#include <cmath>

#include "core/error.hpp"

namespace plumekit::run {

namespace fs = std::filesystem;
using nlohmann::ordered_json;

// Millimetres: finer than any robot's position noise, and a third of the file's size of full
// precision.
double track_metres(double metres) {
  return std::round(metres * 1000.0) / 1000.0;
}

// Four significant digits: the pictures' colour scale needs no more.
double track_reading(double value) {
  if (!(value != 0.0) || !std::isfinite(value)) return std::isfinite(value) ? value : 0.0;
  const double scale = std::pow(10.0, 3 - std::floor(std::log10(std::abs(value))));
  return std::round(value * scale) / scale;
}

namespace {

void add_point(ordered_json& flat, Vec2 p) {
  flat.push_back(track_metres(p.x));
  flat.push_back(track_metres(p.y));
}

ordered_json robot_json(Vec2 start, const std::vector<Step>& steps,
                        const std::vector<Vec2>& approach) {
  ordered_json path = ordered_json::array(), stops = ordered_json::array();
  add_point(path, start);
  for (const Step& s : steps) {
    // path_in starts where the robot stood (the last point already in the path).
    for (std::size_t i = 1; i < s.path_in.size(); ++i)
      add_point(path, s.path_in[i]);
    add_point(stops, s.position);
    stops.push_back(track_reading(s.value));
    stops.push_back(std::round(s.time_s * 10.0) / 10.0);
  }
  for (std::size_t i = 1; i < approach.size(); ++i)
    add_point(path, approach[i]);
  return {{"path", std::move(path)}, {"stops", std::move(stops)}};
}

}  // namespace

ordered_json run_track_json(const RunRecord& run) {
  const LocalizationResult& r = run.result;
  ordered_json robots = ordered_json::array();
  if (r.team.empty()) {
    robots.push_back(robot_json(r.start, r.steps, r.approach));
  } else {
    for (std::size_t k = 0; k < r.team.size(); ++k)
      robots.push_back(
          robot_json(r.team[k].start, r.team[k].steps,
                     static_cast<int>(k) == r.declared_by ? r.approach : std::vector<Vec2>{}));
  }
  return {{"source", {track_metres(run.source.x), track_metres(run.source.y)}},
          {"estimate", {track_metres(run.estimate.x), track_metres(run.estimate.y)}},
          {"robots", std::move(robots)}};
}

ordered_json map_geometry_json(const Map& map) {
  ordered_json obstacles = ordered_json::array(), sources = ordered_json::array();
  for (const Polygon& poly : map.obstacles) {
    ordered_json flat = ordered_json::array();
    for (const Vec2& p : poly)
      add_point(flat, p);
    obstacles.push_back(std::move(flat));
  }
  for (const Vec2& s : map.sources)
    sources.push_back({track_metres(s.x), track_metres(s.y)});
  return {{"name", map.name},
          {"width", track_metres(map.width)},
          {"height", track_metres(map.height)},
          {"obstacles", std::move(obstacles)},
          {"sources", std::move(sources)}};
}

ordered_json tracks_json(const EvaluationResult& result, const std::vector<Map>& maps) {
  ordered_json j{
      {"format", kTracksFormat}, {"maps", ordered_json::array()}, {"runs", ordered_json::array()}};
  for (const Map& m : maps)
    j["maps"].push_back(map_geometry_json(m));
  for (const RunRecord& rec : result.runs)
    j["runs"].push_back(run_track_json(rec));
  return j;
}

namespace {

// Whether `v` is an array of numbers whose count is a multiple of `group` (at least `least`).
bool numbers(const ordered_json& v, std::size_t group, std::size_t least) {
  if (!v.is_array() || v.size() % group != 0 || v.size() < least) return false;
  for (const auto& x : v)
    if (!x.is_number()) return false;
  return true;
}

// Whether `run` is a track as run_track_json writes it.
bool well_formed_track(const ordered_json& run) {
  if (!run.is_object() || !numbers(run.value("source", ordered_json()), 2, 2) ||
      !numbers(run.value("estimate", ordered_json()), 2, 2))
    return false;
  const ordered_json robots = run.value("robots", ordered_json());
  if (!robots.is_array() || robots.empty()) return false;
  for (const auto& robot : robots)
    if (!robot.is_object() || !numbers(robot.value("path", ordered_json()), 2, 2) ||
        !numbers(robot.value("stops", ordered_json()), 4, 0))
      return false;
  return true;
}

}  // namespace

ordered_json parse_tracks(const std::string& bytes, const fs::path& file, std::size_t runs) {
  ordered_json j = ordered_json::parse(bytes, nullptr, false);
  if (!j.is_object() || j.value("format", std::string()) != kTracksFormat)
    throw InputError(file.string() + ": not " + kTracksFormat + " (its \"format\")");
  if (!j.value("maps", ordered_json()).is_array() || !j.value("runs", ordered_json()).is_array())
    throw InputError(file.string() + ": \"maps\" and \"runs\" must be arrays");
  if (j.at("runs").size() != runs)
    throw InputError(file.string() + ": holds " + std::to_string(j.at("runs").size()) +
                     " runs' tracks, runs.csv " + std::to_string(runs) + " runs");
  for (std::size_t k = 0; k < runs; ++k)
    if (!well_formed_track(j.at("runs").at(k)))
      throw InputError(file.string() + ": run " + std::to_string(k) +
                       "'s track lacks its source, estimate or robots' paths");
  return j;
}

ordered_json join_tracks(const std::vector<ordered_json>& parts) {
  ordered_json j{{"format", kTracksFormat},
                 {"maps", parts.empty() ? ordered_json::array() : parts.front().at("maps")},
                 {"runs", ordered_json::array()}};
  for (const ordered_json& p : parts)
    for (const auto& run : p.at("runs"))
      j["runs"].push_back(run);
  return j;
}

}  // namespace plumekit::run
