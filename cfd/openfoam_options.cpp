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

const OptionTable<OpenFoamOptions>& openfoam_option_table() {
  using O = OpenFoamOptions;
  static const OptionTable<O> table{
      "Flow engine (cfd::OpenFoamOptions)",
      {{"flow.engine",
        "--engine",
        enum_field(&O::engine, &to_string, &parse_engine, engine_names()),
        {},
        "Flow solver: " + engine_names() +
            " (openfoam: OpenFOAM's simpleFoam on the same grid, read back into the same files)"},
       {"flow.ranks", "--ranks", &O::ranks, count_range(1, 1024),
        "OpenFOAM engine: MPI ranks (1: serial; N: decomposePar, mpirun -np N simpleFoam "
        "-parallel, reconstructPar)",
        "1 runs simpleFoam serially"},
       {"flow.openfoam_turbulence",
        "--foam-turbulence",
        enum_field(&O::turbulence, &to_string, &parse_foam_turbulence, foam_turbulence_names()),
        {},
        "OpenFOAM engine: turbulence model, " + foam_turbulence_names() +
            " (RANS with wall functions; --nu is then the molecular viscosity)"},
       {"flow.openfoam_tolerance", "--foam-tol", &O::tolerance, real_range(1e-14, 0.1, ""),
        "OpenFOAM engine: stop when every initial residual is below this"},
       {"flow.openfoam_max_iterations", "--foam-max-iter", &O::max_iterations,
        count_range(1, 10000000), "OpenFOAM engine: fail after this many SIMPLE iterations",
        "the default is {default} SIMPLE iterations"},
       {"flow.openfoam_case",
        "--keep-case",
        &O::keep_case,
        {},
        "OpenFOAM engine: write the case into this new or empty folder and keep it (empty: a "
        "temporary, removed)"}}};
  return table;
}

void OpenFoamOptions::validate() const {
  plumekit::validate(openfoam_option_table(), *this);
  if (engine == Engine::OpenFoam) return;
  // The OpenFOAM engine's own options would be ignored by the built-in one: say so.
  const char* const needs = "applies to flow.engine openfoam only";
  if (ranks != 1) throw OptionError("flow.ranks", needs);
  if (turbulence != FoamTurbulence::Laminar) throw OptionError("flow.openfoam_turbulence", needs);
  if (!keep_case.empty()) throw OptionError("flow.openfoam_case", needs);
}

}  // namespace plumekit::cfd
