#include "cfd/wind_file.hpp"

#include <cmath>
#include <nlohmann/json.hpp>
#include <vector>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/npy.hpp"
#include "core/sha256.hpp"
#include "map/map_json.hpp"

namespace plumekit::cfd {

namespace fs = std::filesystem;

std::string map_identity(const Map& map) {
  return sha256_hex(map_to_json(map).dump());
}

namespace {

[[noreturn]] void refuse(const fs::path& file, const std::string& why) {
  throw InputError(file.string() + ": " + why);
}

// The bytes of an array whose checksum wind.json lists, checked against it.
std::string checked_bytes(const fs::path& dir, const nlohmann::json& sums,
                          const std::string& name) {
  const fs::path file = dir / name;
  std::error_code ec;
  if (!fs::is_regular_file(file, ec)) refuse(file, "missing (every plumekit flow output has it)");
  if (!sums.contains(name) || !sums.at(name).is_string())
    refuse(dir / "wind.json", "arrays_sha256." + name + " is missing");
  // One read: the bytes checked are the bytes parsed.
  std::string bytes = read_file(file);
  if (sha256_hex(bytes) != sums.at(name).get<std::string>())
    refuse(file, "does not match its SHA-256 in wind.json (arrays_sha256." + name +
                     "): the file is damaged or was changed; solve the wind again");
  return bytes;
}

// One array whose checksum wind.json lists, with the shape it must have.
std::vector<double> read_array(const fs::path& dir, const nlohmann::json& sums,
                               const std::string& name, std::size_t rows, std::size_t cols) {
  const fs::path file = dir / name;
  const std::string bytes = checked_bytes(dir, sums, name);
  NpyArray a = parse_npy(bytes, file);
  if (a.shape != std::vector<std::size_t>{rows, cols})
    refuse(file, "shape does not match the grid in wind.json (expected (" + std::to_string(rows) +
                     ", " + std::to_string(cols) + "))");
  for (double v : a.values)
    if (!std::isfinite(v)) refuse(file, "holds a value that is not finite");
  return std::move(a.values);
}

int grid_count(const fs::path& json_path, const nlohmann::json& grid, const char* key) {
  if (!grid.contains(key) || !grid.at(key).is_number_integer() || grid.at(key).get<long>() < 1 ||
      grid.at(key).get<long>() > 100000)
    refuse(json_path, std::string("grid.") + key + " must be a positive integer");
  return grid.at(key).get<int>();
}

}  // namespace

WindField read_wind(const fs::path& dir, const Map& map) {
  const fs::path json_path = dir / "wind.json";
  std::error_code ec;
  if (!fs::is_regular_file(json_path, ec))
    refuse(json_path, "missing: give the folder that `plumekit flow MAP --out DIR` wrote");
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(read_file(json_path));
  } catch (const nlohmann::json::exception& e) {
    refuse(json_path, std::string("not valid JSON: ") + e.what());
  }
  if (!j.is_object() || !j.contains("format") || j.at("format") != kWindFormat)
    refuse(json_path, std::string("format must be \"") + kWindFormat + "\"");
  if (!j.contains("arrays_sha256") || !j.at("arrays_sha256").is_object() ||
      !j.contains("map_sha256"))
    refuse(json_path,
           "has no arrays_sha256 / map_sha256: it was written by an older plumekit, whose wind "
           "cannot be read back; solve it again with plumekit flow");
  if (j.at("map_sha256") != map_identity(map))
    refuse(json_path, "map_sha256 is not this map's (" + map.name +
                          "): the wind was solved for another map, or the map changed since; "
                          "solve it again with plumekit flow");
  if (!j.contains("grid") || !j.at("grid").is_object()) refuse(json_path, "grid is missing");
  const nlohmann::json& grid = j.at("grid");
  const int nx = grid_count(json_path, grid, "nx"), ny = grid_count(json_path, grid, "ny");
  const GridShape shape{nx, ny, map.width, map.height};
  for (const auto& [key, expected] : {std::pair{"dx", shape.dx()}, std::pair{"dy", shape.dy()}})
    if (!grid.contains(key) || !grid.at(key).is_number() ||
        std::abs(grid.at(key).get<double>() - expected) > 1e-9 * expected)
      refuse(json_path, std::string("grid.") + key + " does not match the map's size over " +
                            (key[1] == 'x' ? "nx" : "ny") + " cells");
  const nlohmann::json& sums = j.at("arrays_sha256");
  const std::size_t nxs = nx, nys = ny;
  std::vector<double> face_u = read_array(dir, sums, "face_u.npy", nys, nxs + 1);
  std::vector<double> face_v = read_array(dir, sums, "face_v.npy", nys + 1, nxs);
  std::vector<double> pressure = read_array(dir, sums, "p.npy", nys, nxs);
  const std::vector<double> solid_values = read_array(dir, sums, "solid.npy", nys, nxs);
  // The cell-centred velocities are for users (the faces above are what is
  // read), but wind.json vouches for them too: a folder is whole or refused.
  for (const char* name : {"u.npy", "v.npy"})
    checked_bytes(dir, sums, name);
  std::vector<std::uint8_t> solid(solid_values.size());
  for (std::size_t k = 0; k < solid.size(); ++k)
    solid[k] = solid_values[k] != 0.0;
  return WindField(shape, std::move(face_u), std::move(face_v), std::move(pressure),
                   std::move(solid));
}

}  // namespace plumekit::cfd
