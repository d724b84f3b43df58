#pragma once
// The report of an OpenFOAM flow: wind.json's summary and the flow command's
// JSON and text, with the engine, its ranks, turbulence model, iterations,
// residuals and times.
#include <string>

#include <nlohmann/json.hpp>

#include "cfd/openfoam_engine.hpp"

namespace plumekit::cfd {

// summary_json's keys (flow_output.hpp), with "engine": "openfoam" and an
// "openfoam" object; "turbulence" and "convection" are OpenFOAM's.
nlohmann::ordered_json openfoam_summary_json(const OpenFoamResult& r, const FlowOptions& flow);
// The same without the residual history (the flow command's JSON).
nlohmann::ordered_json openfoam_report_json(const OpenFoamResult& r, const FlowOptions& flow);
std::string openfoam_report_text(const OpenFoamResult& r);

}  // namespace plumekit::cfd
