#pragma once
// Writes a solved flow to a directory: wind.json (summary and grid
// convention), u.npy / v.npy / p.npy (float32, (ny, nx), cell-centred, row 0 at
// y = 0, zero inside obstacles), wind.vti (ParaView) and wind.png.
#include <filesystem>

#include <nlohmann/json.hpp>

#include "cfd/flow_policy.hpp"
#include "cfd/flow_solver.hpp"
#include "map/map.hpp"

namespace plumekit::cfd {

nlohmann::ordered_json summary_json(const FlowSummary& s, const WindField& wind,
                                    const FlowOptions& options);

// The flow command's report of a solve: summary_json without the residual
// history, plus "convection_requested" and "fell_back_to_upwind" (the flow
// policy, flow_policy.hpp; "convection" is the scheme used).
nlohmann::ordered_json flow_report_json(const WindResult& w, const FlowOptions& options);
// The same in one line of text: grid, scheme, iterations, residuals, speed,
// time; then, when the grid closed gaps narrower than a cell, a "warning:" line
// naming the narrowest (closed_gaps_text, gap_closing.hpp).
std::string flow_report_text(const WindResult& w);

// VTK XML ImageData with cell data: velocity (3 components), pressure, speed,
// solid; its origin is the map frame's position of the arena's corner.
std::string wind_vti(const WindField& wind, const MapFrame& frame = {});

// All five files; each appears whole or not at all, and none is written
// unless all could be produced.
void write_flow(const std::filesystem::path& dir, const Map& map, const FlowResult& result,
                const FlowOptions& options);
// The same with wind.json's summary given: another engine's (openfoam_report.hpp).
void write_flow(const std::filesystem::path& dir, const Map& map, const WindField& wind,
                const nlohmann::ordered_json& summary);

}  // namespace plumekit::cfd
