#pragma once
// The wind field of each dataset map, kept in the dataset (wind/map-NNNNN/):
// face_u.npy (ny, nx+1) and face_v.npy (ny+1, nx) as float64, so a resumed
// run reads back exactly the wind an uninterrupted run used; u.npy, v.npy
// (ny, nx) float32 cell-centred for users; solid.npy; wind.json with the grid,
// the solver's summary and the SHA-256 of each array file. Written under a
// temporary name, then renamed.
#include <filesystem>
#include <optional>

#include "cfd/flow_solver.hpp"
#include "map/map.hpp"

namespace plumekit::dataset {

void write_wind_cache(const std::filesystem::path& dir, const cfd::FlowResult& flow,
                      const cfd::FlowOptions& options);
// The wind of `map`; nullopt (solve it again) when the directory is missing, incomplete, of an
// older format, a file does not match its checksum, or the grid is not the map's.
std::optional<cfd::WindField> read_wind_cache(const std::filesystem::path& dir, const Map& map);

}  // namespace plumekit::dataset
