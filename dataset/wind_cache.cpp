#include "dataset/wind_cache.hpp"

#include <map>
#include <string>

#include "cfd/flow_output.hpp"
#include "core/atomic_file.hpp"
#include "core/npy.hpp"
#include "core/sha256.hpp"

namespace plumekit::dataset {

namespace fs = std::filesystem;

namespace {
// Version 2 lists the SHA-256 of each array file.
constexpr const char* kWindCacheFormat = "plumekit-wind-cache/2";
}  // namespace

void write_wind_cache(const fs::path& dir, const cfd::FlowResult& flow,
                      const cfd::FlowOptions& options) {
  const cfd::WindField& w = flow.wind;
  const GridShape& g = w.shape();
  const std::size_t nx = g.nx, ny = g.ny;
  AtomicDirectory out(dir);
  const fs::path& tmp = out.path();
  std::vector<double> solid(w.solid_cells().begin(), w.solid_cells().end());
  const std::map<std::string, std::string> files{
      {"face_u.npy", npy_float64(w.face_u(), {ny, nx + 1})},
      {"face_v.npy", npy_float64(w.face_v(), {ny + 1, nx})},
      {"u.npy", npy_float32(w.u(), {ny, nx})},
      {"v.npy", npy_float32(w.v(), {ny, nx})},
      {"solid.npy", npy_float32(solid, {ny, nx})},
  };
  nlohmann::ordered_json sums = nlohmann::ordered_json::object();
  for (const auto& [name, bytes] : files) {
    write_file_atomic(tmp / name, bytes);
    sums[name] = sha256_hex(bytes);
  }
  nlohmann::ordered_json j{
      {"format", kWindCacheFormat},
      {"grid", {{"nx", g.nx}, {"ny", g.ny}, {"width", g.width}, {"height", g.height}}},
      {"convention",
       "face_u[j][i] is the x-velocity at x = i*dx, y = (j+0.5)*dy; "
       "face_v[j][i] the y-velocity at x = (i+0.5)*dx, y = j*dy; u, v, solid "
       "cell-centred; row 0 at y = 0"}};
  nlohmann::ordered_json s = cfd::summary_json(flow.summary, w, options);
  // Timings would make two identical runs differ byte for byte.
  s.erase("residual_history");
  s.erase("seconds");
  s.erase("seconds_breakdown");
  j["flow"] = s;
  j["sha256"] = sums;
  write_file_atomic(tmp / "wind.json", j.dump(2) + "\n");  // last: marks the cache complete
  out.commit();
}

std::optional<cfd::WindField> read_wind_cache(const fs::path& dir, const Map& map) {
  std::error_code ec;
  if (!fs::is_regular_file(dir / "wind.json", ec)) return std::nullopt;
  try {
    const auto j = nlohmann::json::parse(read_file(dir / "wind.json"));
    // An older cache carries no checksums: it cannot be trusted, so it is solved again.
    if (j.at("format") != kWindCacheFormat) return std::nullopt;
    // Each file is read once: the bytes checked are the bytes parsed.
    std::map<std::string, std::string> bytes;
    for (const char* name : {"face_u.npy", "face_v.npy", "u.npy", "v.npy", "solid.npy"}) {
      if (!fs::is_regular_file(dir / name, ec)) return std::nullopt;
      bytes[name] = read_file(dir / name);
      if (sha256_hex(bytes[name]) != j.at("sha256").at(name).get<std::string>())
        return std::nullopt;
    }
    const GridShape g{j.at("grid").at("nx").get<int>(), j.at("grid").at("ny").get<int>(),
                      j.at("grid").at("width").get<double>(),
                      j.at("grid").at("height").get<double>()};
    if (g.nx < 1 || g.ny < 1 || g.width != map.width || g.height != map.height) return std::nullopt;
    NpyArray fu = parse_npy(bytes["face_u.npy"], dir / "face_u.npy");
    NpyArray fv = parse_npy(bytes["face_v.npy"], dir / "face_v.npy");
    NpyArray solid = parse_npy(bytes["solid.npy"], dir / "solid.npy");
    if (fu.shape != std::vector<std::size_t>{std::size_t(g.ny), std::size_t(g.nx) + 1} ||
        fv.shape != std::vector<std::size_t>{std::size_t(g.ny) + 1, std::size_t(g.nx)} ||
        solid.shape != std::vector<std::size_t>{std::size_t(g.ny), std::size_t(g.nx)})
      return std::nullopt;
    std::vector<std::uint8_t> s(g.size());
    for (std::size_t k = 0; k < g.size(); ++k)
      s[k] = solid.values[k] != 0.0;
    return cfd::WindField(g, std::move(fu.values), std::move(fv.values),
                          std::vector<double>(g.size(), 0.0), std::move(s));
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

}  // namespace plumekit::dataset
