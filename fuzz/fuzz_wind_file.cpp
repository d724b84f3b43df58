// Fuzzes the wind folder reader (cfd/wind_file: read_wind), what `plumekit flow` writes and
// `plume`/`localize --wind DIR` read. An input is wind.json's text; after a NUL byte, optionally,
// one byte choosing an array (face_u, face_v, p, solid, u, v: the byte modulo 6) and that array's
// .npy bytes. The reader takes a folder, so the target keeps one in a private temporary folder
// holding the arrays of a fixed 6 x 4 grid on the map it reads for (a 3 x 2 m default arena),
// zeros, with the chosen array replaced. Each input is read twice: as it is, and "resealed" (its
// arrays_sha256 recomputed from the files and its map_sha256 set to the map's), so that mutated
// JSON and arrays get past the checksums to the parsers and shape checks behind them. Bad input
// must end in InputError; anything else escaping is a bug. An accepted wind must hold finite face
// velocities of the grid's shape.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "cfd/wind_file.hpp"
#include "core/error.hpp"
#include "core/npy.hpp"
#include "core/sha256.hpp"
#include "fuzz/scratch_folder.hpp"

namespace fs = std::filesystem;
using plumekit::Map;
using plumekit::fuzz::scratch_folder;
using plumekit::fuzz::write_file;

namespace {

constexpr const char* kArrays[] = {"face_u.npy", "face_v.npy", "p.npy",
                                   "solid.npy",  "u.npy",      "v.npy"};

// The fixed grid's arrays, as `plumekit flow` lays them out (zeros).
std::string array_bytes(std::size_t k) {
  constexpr std::size_t nx = 6, ny = 4;
  switch (k) {
    case 0:
      return plumekit::npy_float64(std::vector<double>(ny * (nx + 1), 0.0), {ny, nx + 1});
    case 1:
      return plumekit::npy_float64(std::vector<double>((ny + 1) * nx, 0.0), {ny + 1, nx});
    default:
      return plumekit::npy_float32(std::vector<double>(ny * nx, 0.0), {ny, nx});
  }
}

// Reads the folder; aborts on anything but InputError, or an accepted wind that is not whole.
void read_once(const fs::path& dir, const Map& map) {
  try {
    const plumekit::cfd::WindField w = plumekit::cfd::read_wind(dir, map);
    const auto& s = w.shape();
    if (w.face_u().size() != static_cast<std::size_t>(s.ny) * (s.nx + 1) ||
        w.face_v().size() != static_cast<std::size_t>(s.ny + 1) * s.nx ||
        w.solid_cells().size() != s.size())
      std::abort();
    for (const auto* face : {&w.face_u(), &w.face_v()})
      for (double v : *face)
        if (!std::isfinite(v)) std::abort();
  } catch (const plumekit::InputError&) {
  }
}

// wind.json with its checksums made to match the folder and the map, or "" when it is not a
// JSON object.
std::string resealed(std::string_view json_text, const fs::path& dir, const Map& map) {
  nlohmann::json j = nlohmann::json::parse(json_text, nullptr, false);
  if (j.is_discarded() || !j.is_object()) return "";
  nlohmann::json sums = nlohmann::json::object();
  for (const char* name : kArrays) {
    std::ifstream in(dir / name, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    sums[name] = plumekit::sha256_hex(bytes);
  }
  j["arrays_sha256"] = sums;
  j["map_sha256"] = plumekit::cfd::map_identity(map);
  return j.dump();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const Map map = plumekit::default_arena(3.0, 2.0);
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  const std::size_t nul = input.find('\0');
  const std::string_view json_text = input.substr(0, nul);
  const fs::path& dir = scratch_folder("wind");
  for (std::size_t k = 0; k < std::size(kArrays); ++k)
    write_file(dir / kArrays[k], array_bytes(k));
  if (nul != std::string_view::npos && nul + 1 < input.size()) {
    const std::size_t k = static_cast<unsigned char>(input[nul + 1]) % std::size(kArrays);
    write_file(dir / kArrays[k], input.substr(nul + 2));
  }
  write_file(dir / "wind.json", json_text);
  read_once(dir, map);
  if (const std::string again = resealed(json_text, dir, map); !again.empty()) {
    write_file(dir / "wind.json", again);
    read_once(dir, map);
  }
  return 0;
}
