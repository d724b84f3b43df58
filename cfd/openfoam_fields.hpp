#pragma once
// Reading OpenFOAM's ASCII results back onto plumekit's grid.
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "cfd/flow_solver.hpp"
#include "cfd/openfoam_case.hpp"

namespace plumekit::cfd {

// A field's values: `uniform` holds one entry of `width` numbers, else one
// per cell or face.
struct FoamValues {
  bool uniform = false;
  std::vector<double> values;
  // n entries of `width` numbers (a uniform value repeated); InputError if the
  // count is neither.
  std::vector<double> expand(std::size_t n, int width, const std::string& what) const;
};

// internalField and each patch's `value` of an ASCII field file (volume or
// surface field); InputError when it cannot be parsed.
struct FoamField {
  FoamValues internal;
  std::map<std::string, FoamValues> patches;
};
FoamField read_foam_field(const std::filesystem::path& file, int width);

// The latest time folder of a case other than 0 ("" when there is none).
std::string latest_time(const std::filesystem::path& dir);

// The wind from OpenFOAM's face fluxes phi (each face's normal velocity, so
// the field is as mass-conserving as OpenFOAM's) and cell pressures p; the
// summary's inflow, outflow, mass imbalance and grid are filled in.
FlowResult wind_from_foam(const StaggeredGrid& grid, const FoamMesh& mesh, const FoamField& phi,
                          const FoamField& p, double nu);

}  // namespace plumekit::cfd
