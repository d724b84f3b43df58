#pragma once
// The OpenFOAM flow engine: the same steady flow as cfd::solve, computed by
// OpenFOAM's simpleFoam (serial, or decomposed over MPI ranks), optionally
// with the k-omega SST RANS model, and read back into plumekit's WindField.
//
//   cfd::OpenFoamOptions foam;  foam.engine = cfd::Engine::OpenFoam;  foam.ranks = 2;
//   cfd::OpenFoamResult r = cfd::solve_openfoam(map, flow_options, foam, work_dir);
//   r.flow.wind.at({2.0, 1.5});
//
// The mesh is the built-in solver's grid (StaggeredGrid) minus its solid
// cells, and each boundary face's condition is the grid's: a fixed non-zero
// velocity is an inlet face, an outflow face an outlet, any other a no-slip
// wall (docs/design/flow-solver.md, "OpenFOAM engine").
#include <filesystem>
#include <map>
#include <string>

#include "cfd/flow_solver.hpp"
#include "map/map.hpp"

namespace plumekit::cfd {

enum class Engine { Builtin, OpenFoam };
// OpenFOAM's turbulence: none, or the k-omega SST RANS model with wall functions.
enum class FoamTurbulence { Laminar, KOmegaSST };

const char* to_string(Engine e);
const char* to_string(FoamTurbulence t);
std::string engine_names();
std::string foam_turbulence_names();
// OptionError on "flow.engine" / "flow.openfoam_turbulence" for an unknown name.
Engine parse_engine(const std::string& name);
FoamTurbulence parse_foam_turbulence(const std::string& name);

struct OpenFoamOptions {
  Engine engine = Engine::Builtin;  // flow.engine
  // 1: serial simpleFoam; N > 1: decomposePar (method simple) over N MPI ranks.
  int ranks = 1;                                        // flow.ranks
  FoamTurbulence turbulence = FoamTurbulence::Laminar;  // flow.openfoam_turbulence
  // simpleFoam stops when every equation's initial residual is below this
  // (residualControl); not converged within max_iterations is an error.
  double tolerance = 1e-6;    // flow.openfoam_tolerance
  int max_iterations = 5000;  // flow.openfoam_max_iterations
  // Write the case here and keep it (a new or empty folder); empty: the case
  // is a temporary inside the work folder, removed after the run.
  std::string keep_case;  // flow.openfoam_case

  // OptionError naming the field and its allowed range, or an OpenFOAM-only
  // field set (ranks, turbulence, case) with the built-in engine.
  void validate() const;
};

// Its options table (core/option_table.hpp): validate()'s ranges, `flow`'s engine flags and
// docs/options.md. cfd/openfoam_options.cpp.
const OptionTable<OpenFoamOptions>& openfoam_option_table();

// What the OpenFOAM run did.
struct OpenFoamRun {
  int ranks = 1;
  FoamTurbulence turbulence = FoamTurbulence::Laminar;
  int iterations = 0;
  bool converged = false;
  std::map<std::string, double> residuals;  // last initial residual per equation (Ux, Uy, p, ...)
  double case_seconds = 0.0;                // writing the case (mesh, fields, dictionaries)
  double solver_seconds = 0.0;              // decomposePar + simpleFoam + reconstructPar
  double read_seconds = 0.0;                // reading the fields back
  std::string kept_case;                    // the case folder, when kept
};

struct OpenFoamResult {
  FlowResult flow;
  OpenFoamRun run;
};

// Solves the flow of `map` with OpenFOAM. `work_dir` is an existing folder the
// temporary case goes into (unless foam.keep_case names one). Throws
// OptionError for bad options, InputError when an OpenFOAM program is missing
// or fails, ConvergenceError when simpleFoam does not converge.
OpenFoamResult solve_openfoam(const Map& map, const FlowOptions& flow, const OpenFoamOptions& foam,
                              const std::filesystem::path& work_dir);

}  // namespace plumekit::cfd
