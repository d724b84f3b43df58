#pragma once
// The runs' ways as data: tracks.json of an evaluation (docs/report.md): each run's robots, the
// way each drove and its stops with their readings, and the maps' geometry they are drawn on.
// `evaluate` writes it beside runs.csv (in run order), a part keeps its runs' tracks, `evaluate
// merge` joins them, and report.html draws them.
#include <filesystem>
#include <vector>

#include <nlohmann/json.hpp>

#include "map/map.hpp"
#include "run/evaluation.hpp"

namespace plumekit::run {

inline constexpr const char* kTracksFormat = "plumekit-tracks/1";
inline constexpr const char* kTracksFile = "tracks.json";

// A position as tracks.json holds it (to the millimetre), and a reading (four significant
// digits).
double track_metres(double metres);
double track_reading(double value);

// One run: {"source": [x, y], "estimate": [x, y], "robots": [{"path": [x, y, ...], "stops": [x,
// y, value, time_s, ...]}]}, in the arena's metres (as the map file's geometry, not runs.csv's
// map frame), rounded to the millimetre; a path starts at the robot's start.
nlohmann::ordered_json run_track_json(const RunRecord& run);

// A map's outline, obstacles and sources, for drawing: {"name", "width", "height", "obstacles":
// [[x, y, ...], ...], "sources": [[x, y], ...]}.
nlohmann::ordered_json map_geometry_json(const Map& map);

// tracks.json of `result`: the format, every map's geometry and every run's track, in run order.
nlohmann::ordered_json tracks_json(const EvaluationResult& result, const std::vector<Map>& maps);

// Parses and checks tracks.json's `bytes` read from `file`: its format, and one track per run of
// `runs` (a part's or an evaluation's). InputError naming the file otherwise.
nlohmann::ordered_json parse_tracks(const std::string& bytes, const std::filesystem::path& file,
                                    std::size_t runs);

// The tracks of parts, in order, as one evaluation's (the maps of the first; the parts share them).
nlohmann::ordered_json join_tracks(const std::vector<nlohmann::ordered_json>& parts);

}  // namespace plumekit::run
