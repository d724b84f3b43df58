// OpenFoamOptions: names, parsing and validation (declared in openfoam_engine.hpp).
#include "cfd/openfoam_engine.hpp"
#include "core/error.hpp"
#include "core/option_check.hpp"

namespace plumekit::cfd {

const char* to_string(Engine e) {
  return e == Engine::OpenFoam ? "openfoam" : "builtin";
}
const char* to_string(FoamTurbulence t) {
  return t == FoamTurbulence::KOmegaSST ? "kOmegaSST" : "laminar";
}
std::string engine_names() {
  return "builtin, openfoam";
}
std::string foam_turbulence_names() {
  return "laminar, kOmegaSST";
}

Engine parse_engine(const std::string& name) {
  check_name("flow.engine", name, {"builtin", "openfoam"});
  return name == "openfoam" ? Engine::OpenFoam : Engine::Builtin;
}

FoamTurbulence parse_foam_turbulence(const std::string& name) {
  check_name("flow.openfoam_turbulence", name, {"laminar", "kOmegaSST"});
  return name == "kOmegaSST" ? FoamTurbulence::KOmegaSST : FoamTurbulence::Laminar;
}

void OpenFoamOptions::validate() const {
  check_count("flow.ranks", ranks, 1, 1024, "1 runs simpleFoam serially");
  check_range("flow.openfoam_tolerance", tolerance, 1e-14, 0.1, "", "the default is 1e-06");
  check_count("flow.openfoam_max_iterations", max_iterations, 1, 10000000,
              "the default is 5000 SIMPLE iterations");
  if (engine == Engine::OpenFoam) return;
  // The OpenFOAM engine's own options would be ignored by the built-in one: say so.
  const char* const needs = "applies to flow.engine openfoam only";
  if (ranks != 1) throw OptionError("flow.ranks", needs);
  if (turbulence != FoamTurbulence::Laminar) throw OptionError("flow.openfoam_turbulence", needs);
  if (!keep_case.empty()) throw OptionError("flow.openfoam_case", needs);
}

}  // namespace plumekit::cfd
