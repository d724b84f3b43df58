#include "cfd/flow_output.hpp"

#include <sstream>

#include "cfd/flow_render.hpp"
#include "cfd/wind_file.hpp"
#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/image_io.hpp"
#include "core/npy.hpp"
#include "core/sha256.hpp"
#include "core/vti.hpp"

namespace plumekit::cfd {

nlohmann::ordered_json summary_json(const FlowSummary& s, const WindField& wind,
                                    const FlowOptions& options) {
  nlohmann::ordered_json j;
  j["format"] = kWindFormat;
  j["grid"] = {{"nx", s.nx},
               {"ny", s.ny},
               {"dx", s.dx},
               {"dy", s.dy},
               {"origin", {0.0, 0.0}},
               {"convention",
                "arrays (ny, nx), row-major, row 0 at y = 0, cell-centred: value [j][i] at "
                "((i + 0.5) dx, (j + 0.5) dy); zero inside obstacles"}};
  j["cell"] = s.cell != 0.0 ? s.cell : options.cell;  // the default resolved (resolved_cell)
  // Only when some were closed, so that earlier outputs (and caches) keep their bytes.
  if (s.closed_gaps.count > 0) {
    nlohmann::ordered_json narrowest = nlohmann::ordered_json::array();
    for (const ClosedGap& g : s.closed_gaps.narrowest)
      narrowest.push_back({{"between", g.between}, {"width", g.width}, {"at", {g.at.x, g.at.y}}});
    j["closed_gaps"] = {{"count", s.closed_gaps.count},
                        {"frame", "map"},
                        {"narrowest", narrowest},
                        {"cell_keeping_them_open", s.closed_gaps.open_cell}};
  }
  if (!s.thin_walls.walls.empty()) {  // likewise only when some leak
    nlohmann::ordered_json walls = nlohmann::ordered_json::array();
    for (const ThinWall& w : s.thin_walls.walls)
      walls.push_back({{"obstacle", w.obstacle},
                       {"at", {w.at.x, w.at.y}},
                       {"thickness", w.thickness},
                       {"leaking_faces", w.leaks}});
    j["thin_walls"] = {{"count", walls.size()},
                       {"frame", "map"},
                       {"walls", walls},
                       {"cell_resolving_them", s.thin_walls.resolving_cell}};
  }
  j["viscosity"] = s.nu;
  j["turbulence"] = to_string(s.turbulence);
  j["convection"] = to_string(s.convection);
  j["tolerance"] = s.tolerance;
  j["converged"] = s.converged;
  j["iterations"] = s.iterations;
  j["factorizations"] = s.factorizations;
  j["linear_solver"] = s.linear_solver;
  j["final_residuals"] = {{"momentum", s.momentum_residual}, {"continuity", s.continuity_residual}};
  j["inflow_m2_per_s"] = s.inflow;
  j["outflow_m2_per_s"] = s.outflow;
  j["mass_imbalance"] = s.mass_imbalance;
  j["max_speed"] = wind.max_speed();
  j["max_eddy_viscosity"] = s.max_eddy_viscosity;
  j["seconds"] = s.seconds;
  j["seconds_breakdown"] = {{"coarse_grids", s.coarse_seconds},
                            {"factorizations", s.factor_seconds},
                            {"solves", s.solve_seconds}};
  nlohmann::ordered_json history = nlohmann::ordered_json::array();
  for (const IterationRecord& r : s.history)
    history.push_back({r.momentum, r.continuity});
  j["residual_history"] = history;
  return j;
}

nlohmann::ordered_json flow_report_json(const WindResult& w, const FlowOptions& options) {
  nlohmann::ordered_json j = summary_json(w.flow.summary, w.flow.wind, options);
  j.erase("residual_history");
  j["engine"] = "builtin";
  j["convection_requested"] = to_string(w.requested);
  j["fell_back_to_upwind"] = w.fell_back();
  return j;
}

std::string flow_report_text(const WindResult& w) {
  const FlowSummary& s = w.flow.summary;
  std::ostringstream text;
  text.precision(3);
  text << s.nx << " x " << s.ny << " cells, " << to_string(w.scheme()) << " convection";
  if (w.fell_back())
    text << " (" << to_string(w.requested) << " did not converge: fell back to upwind)";
  text << ", " << s.iterations << " Newton iterations (" << s.factorizations
       << " factorizations), residuals " << std::scientific << s.momentum_residual << " / "
       << s.continuity_residual << ", mass imbalance " << s.mass_imbalance << std::defaultfloat
       << ", max speed " << s.max_speed << " m/s, " << s.seconds << " s";
  if (s.closed_gaps.count > 0) text << "\nwarning: " << closed_gaps_text(s.closed_gaps, s.cell);
  return text.str();
}

std::string wind_vti(const WindField& wind, const MapFrame& frame) {
  const GridShape& g = wind.shape();
  VtiArray velocity{"velocity", 3, {}}, pressure{"pressure", 1, {}}, speed{"speed", 1, {}},
      solid{"solid", 1, {}};
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      const Vec2 v = wind.cell_velocity(i, j);
      velocity.values.insert(velocity.values.end(),
                             {static_cast<float>(v.x), static_cast<float>(v.y), 0.0f});
      pressure.values.push_back(static_cast<float>(wind.cell_pressure(i, j)));
      speed.values.push_back(static_cast<float>(norm(v)));
      solid.values.push_back(wind.solid(i, j) ? 1.0f : 0.0f);
    }
  return vti_cell_data(g, {velocity, pressure, speed, solid}, "velocity", "speed", frame.origin);
}

void write_flow(const std::filesystem::path& dir, const Map& map, const FlowResult& result,
                const FlowOptions& options) {
  write_flow(dir, map, result.wind, summary_json(result.summary, result.wind, options));
}

void write_flow(const std::filesystem::path& dir, const Map& map, const WindField& wind,
                const nlohmann::ordered_json& summary) {
  const std::vector<std::size_t> shape{static_cast<std::size_t>(wind.shape().ny),
                                       static_cast<std::size_t>(wind.shape().nx)};
  const std::string png = encode_png(render_wind(map, wind));
  // A framed map's grid sits at its origin in the map frame.
  nlohmann::ordered_json json = summary;
  if (map.has_frame() && json.contains("grid")) {
    json["grid"]["origin"] = {map.frame.origin.x, map.frame.origin.y};
    json["grid"]["convention"] =
        "arrays (ny, nx), row-major, row 0 at the lowest y, cell-centred: value [j][i] at origin "
        "+ ((i + 0.5) dx, (j + 0.5) dy) in the map frame; zero inside obstacles";
  }
  // Everything is produced in memory first, so a failure leaves no partial set.
  const std::size_t nx = shape[1], ny = shape[0];
  const std::vector<double> solid(wind.solid_cells().begin(), wind.solid_cells().end());
  std::vector<std::pair<const char*, std::string>> files = {
      {"u.npy", npy_float32(wind.u(), shape)},
      {"v.npy", npy_float32(wind.v(), shape)},
      {"p.npy", npy_float32(wind.p(), shape)},
      // The faces as solved (float64), so `plume --wind` and `localize --wind`
      // read back exactly this wind (wind_file.hpp).
      {"face_u.npy", npy_float64(wind.face_u(), {ny, nx + 1})},
      {"face_v.npy", npy_float64(wind.face_v(), {ny + 1, nx})},
      {"solid.npy", npy_float32(solid, shape)},
  };
  json["map_sha256"] = map_identity(map);
  nlohmann::ordered_json sums = nlohmann::ordered_json::object();
  for (const auto& [name, bytes] : files)
    sums[name] = sha256_hex(bytes);
  json["arrays_sha256"] = sums;
  files.emplace_back("wind.vti", wind_vti(wind, map.frame));
  files.emplace_back("wind.png", png);
  files.emplace_back("wind.json", json.dump(2) + "\n");  // last: marks the set complete
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw InputError(dir.string() + ": cannot create the output directory: " + ec.message());
  for (const auto& [name, bytes] : files)
    write_file_atomic(dir / name, bytes);
}

}  // namespace plumekit::cfd
