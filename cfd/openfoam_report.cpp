#include "cfd/openfoam_report.hpp"

#include <sstream>

#include "cfd/flow_output.hpp"
#include "cfd/gap_closing.hpp"

namespace plumekit::cfd {

namespace {
// The OpenFOAM case's convection scheme (openfoam_case.cpp).
constexpr const char* kFoamConvection = "linearUpwind";
}  // namespace

nlohmann::ordered_json openfoam_summary_json(const OpenFoamResult& r, const FlowOptions& flow) {
  nlohmann::ordered_json j = summary_json(r.flow.summary, r.flow.wind, flow);
  j.erase("factorizations");
  j.erase("linear_solver");
  j.erase("seconds_breakdown");
  j.erase("max_eddy_viscosity");
  j["engine"] = "openfoam";
  j["turbulence"] = to_string(r.run.turbulence);
  j["convection"] = kFoamConvection;
  j["final_residuals"] = r.run.residuals;
  j["openfoam"] = {{"solver", "simpleFoam (SIMPLEC)"},
                   {"ranks", r.run.ranks},
                   {"iterations", r.run.iterations},
                   {"seconds_breakdown",
                    {{"case", r.run.case_seconds},
                     {"solver", r.run.solver_seconds},
                     {"read_back", r.run.read_seconds}}}};
  if (!r.run.kept_case.empty()) j["openfoam"]["case"] = r.run.kept_case;
  j["residual_history"] = nlohmann::ordered_json::array();
  return j;
}

nlohmann::ordered_json openfoam_report_json(const OpenFoamResult& r, const FlowOptions& flow) {
  nlohmann::ordered_json j = openfoam_summary_json(r, flow);
  j.erase("residual_history");
  return j;
}

std::string openfoam_report_text(const OpenFoamResult& r) {
  const FlowSummary& s = r.flow.summary;
  std::ostringstream text;
  text.precision(3);
  text << s.nx << " x " << s.ny << " cells, OpenFOAM simpleFoam on " << r.run.ranks
       << (r.run.ranks == 1 ? " rank" : " MPI ranks") << ", " << to_string(r.run.turbulence) << ", "
       << kFoamConvection << " convection, " << r.run.iterations << " SIMPLE iterations, residuals";
  for (const auto& [name, value] : r.run.residuals)
    text << " " << name << " " << std::scientific << value << std::defaultfloat;
  text << ", mass imbalance " << std::scientific << s.mass_imbalance << std::defaultfloat
       << ", max speed " << s.max_speed << " m/s, " << s.seconds << " s";
  if (!r.run.kept_case.empty()) text << "; case kept in " << r.run.kept_case;
  if (s.closed_gaps.count > 0) text << "\nwarning: " << closed_gaps_text(s.closed_gaps, s.cell);
  return text.str();
}

}  // namespace plumekit::cfd
