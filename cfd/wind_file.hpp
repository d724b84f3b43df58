#pragma once
// Reads back the wind that `plumekit flow` wrote (either engine), so that later
// stages (`plume --wind`, `localize --wind`) can use a wind solved once, or by
// OpenFOAM, instead of solving their own. The face velocities are read from
// face_u.npy / face_v.npy (float64, as solved); wind.json lists the SHA-256 of
// every array and of the map the wind was solved for, and each is checked.
#include <filesystem>
#include <string>

#include "cfd/wind_field.hpp"
#include "map/map.hpp"

namespace plumekit::cfd {

// wind.json's "format", which `plumekit flow` writes and read_wind requires.
inline constexpr const char* kWindFormat = "plumekit-wind/1";

// The `--wind DIR` option's help (plume, localize).
inline constexpr const char* kWindHelp =
    "Use the wind in this folder (what `plumekit flow MAP --out DIR` wrote for this map, with "
    "either engine) instead of solving one; --cell then does not apply";

// The identity of a map that wind.json records ("map_sha256"): the SHA-256 of
// its canonical JSON, so two files with the same map give the same value.
std::string map_identity(const Map& map);

// The wind in `dir` (a `plumekit flow` output) for `map`. InputError naming
// the file and field when a file is missing, damaged (a checksum differs), of
// another format or grid, not finite, or solved for another map.
WindField read_wind(const std::filesystem::path& dir, const Map& map);

}  // namespace plumekit::cfd
