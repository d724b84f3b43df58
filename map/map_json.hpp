#pragma once
// The plumekit-map/2 JSON format, and /1 before it (docs/map-format.md).
// Reading validates everything; a fault throws InputError naming the file,
// the key (e.g. "obstacles[2][1]") and what is wrong.
#include <filesystem>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "map/map.hpp"

namespace plumekit {

inline constexpr const char* kMapFormat = "plumekit-map/2";
inline constexpr const char* kMapFormatV1 = "plumekit-map/1";

// Parse and validate map text; `origin` names the file in messages.
Map parse_map(std::string_view text, const std::string& origin);
Map read_map(const std::filesystem::path& path);

// A framed map's file holds whole micrometres, its frame's origin too: `origin`
// rounded so. import-ros rounds a YAML's origin with it, so that a map in
// memory is the map its file reads back as (an origin of -9.53674e-07 would
// otherwise put the arena's edge at -1e-06 in the file, outside the arena).
Vec2 file_origin(Vec2 origin);

// Checks the geometry of a map already in memory (the same checks read_map
// makes after parsing): frame, polygons, openings, sources.
void validate_map(const Map& map, const std::string& origin);

// The file's JSON: plumekit-map/1 for a map read as /1 (format_version 1),
// else /2, with every coordinate in the map frame.
nlohmann::ordered_json map_to_json(const Map& map);
// The file's text, one line per key, polygon or source; validates first
// (InputError naming `origin`).
std::string map_file_text(const Map& map, const std::string& origin);
// Validates, then writes atomically (no partial file on failure). Replaces an
// existing file: a command writing where the user said checks the output rule
// first (check_output_file in output_target.hpp).
void write_map(const Map& map, const std::filesystem::path& path);

}  // namespace plumekit
