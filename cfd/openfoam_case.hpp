#pragma once
// An OpenFOAM case for a map's grid: the polyMesh written directly (the
// structured grid minus its solid cells, one cell thick), the initial fields
// with each boundary face's condition taken from the StaggeredGrid, and the
// system/constant dictionaries.
#include <array>
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "cfd/openfoam_engine.hpp"
#include "cfd/staggered_grid.hpp"

namespace plumekit::cfd {

// Where an OpenFOAM face lies on the MAC grid: component c (0: normal to x,
// 1: normal to y), StaggeredGrid::face index, and the sign that turns the
// face's flux (along OpenFOAM's normal) into the MAC velocity (+x / +y).
struct MacFace {
  int c = 0;
  std::size_t f = 0;
  int sign = 1;
};

struct FoamPatch {
  std::string name;
  std::string type;  // patch, wall, empty
  int start = 0;
  int size = 0;
};

// The mesh: internal faces in upper-triangular order, then the patches inlet,
// outlet, walls, frontAndBack. OpenFOAM cell k is plumekit cell cell_of[k]
// (row-major fluid cells, in order).
struct FoamMesh {
  std::vector<std::array<double, 3>> points;
  std::vector<std::array<int, 4>> faces;
  std::vector<int> owner;
  std::vector<int> neighbour;  // internal faces only
  std::vector<FoamPatch> patches;
  std::vector<std::size_t> cell_of;
  std::vector<MacFace> mac;  // every face but frontAndBack's
  double depth = 0.0;        // the one cell's thickness in z
  int n_internal() const { return static_cast<int>(neighbour.size()); }
  const FoamPatch& patch(const std::string& name) const;
};

FoamMesh build_foam_mesh(const StaggeredGrid& grid);

// Writes constant/polyMesh, 0/, constant/ and system/ into `dir` (which exists).
void write_foam_case(const std::filesystem::path& dir, const FoamMesh& mesh,
                     const StaggeredGrid& grid, const FlowOptions& flow,
                     const OpenFoamOptions& foam);

}  // namespace plumekit::cfd
