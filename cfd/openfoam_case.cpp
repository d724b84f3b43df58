#include "cfd/openfoam_case.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>

#include "core/error.hpp"

namespace plumekit::cfd {

namespace fs = std::filesystem;

namespace {

// Patch order in the boundary file (frontAndBack last).
enum PatchId { kInlet, kOutlet, kWalls, kFrontAndBack, kPatchCount };
const char* const kPatchNames[kPatchCount] = {"inlet", "outlet", "walls", "frontAndBack"};
const char* const kPatchTypes[kPatchCount] = {"patch", "patch", "wall", "empty"};

// frontAndBack faces lie on no MAC face.
constexpr MacFace kNoMacFace{0, 0, 0};

struct Face {
  std::array<int, 4> nodes;
  int owner;
  MacFace mac;
};

// Builds the mesh of one grid: node numbering, then faces by kind.
class MeshBuilder {
 public:
  explicit MeshBuilder(const StaggeredGrid& grid) : g_(grid), nx_(grid.nx()), ny_(grid.ny()) {}

  FoamMesh build() {
    number_cells_and_nodes();
    for (std::size_t k = 0; k < m_.cell_of.size(); ++k)
      add_cell_faces(static_cast<int>(k));
    for (int p = 0; p < kPatchCount; ++p) {
      FoamPatch patch{kPatchNames[p], kPatchTypes[p], static_cast<int>(m_.faces.size()),
                      static_cast<int>(boundary_[p].size())};
      m_.patches.push_back(patch);
      for (const Face& f : boundary_[p])
        push(f);
    }
    return std::move(m_);
  }

 private:
  bool fluid(int i, int j) const {
    return i >= 0 && i < nx_ && j >= 0 && j < ny_ && !g_.solid(g_.shape().index(i, j));
  }
  // Node (i, j) in layer z (0: z = 0, 1: z = depth).
  int node(int i, int j, int z) const {
    return node_id_[static_cast<std::size_t>(j) * (nx_ + 1) + i] + z * n_nodes_;
  }

  void number_cells_and_nodes() {
    const GridShape& s = g_.shape();
    cell_id_.assign(s.size(), -1);
    node_id_.assign(static_cast<std::size_t>(nx_ + 1) * (ny_ + 1), -1);
    for (int j = 0; j < ny_; ++j)
      for (int i = 0; i < nx_; ++i) {
        if (!fluid(i, j)) continue;
        cell_id_[s.index(i, j)] = static_cast<int>(m_.cell_of.size());
        m_.cell_of.push_back(s.index(i, j));
        for (int dj = 0; dj < 2; ++dj)
          for (int di = 0; di < 2; ++di)
            node_id_[static_cast<std::size_t>(j + dj) * (nx_ + 1) + i + di] = 0;
      }
    m_.depth = std::min(s.dx(), s.dy());
    for (int z = 0; z < 2; ++z)
      for (int j = 0; j <= ny_; ++j)
        for (int i = 0; i <= nx_; ++i) {
          int& id = node_id_[static_cast<std::size_t>(j) * (nx_ + 1) + i];
          if (id < 0) continue;
          if (z == 0) id = n_nodes_++;
          m_.points.push_back({i * s.dx(), j * s.dy(), z * m_.depth});
        }
  }

  // Faces with normal +x at x_i and +y at y_j, beside cell (i, j) / (i, j - 1).
  std::array<int, 4> x_face(int i, int j) const {
    return {node(i, j, 0), node(i, j + 1, 0), node(i, j + 1, 1), node(i, j, 1)};
  }
  std::array<int, 4> y_face(int i, int j) const {
    return {node(i, j, 0), node(i, j, 1), node(i + 1, j, 1), node(i + 1, j, 0)};
  }
  static std::array<int, 4> reversed(std::array<int, 4> n) {
    std::reverse(n.begin(), n.end());
    return n;
  }

  void add_cell_faces(int k) {
    const int i = static_cast<int>(m_.cell_of[k] % nx_), j = static_cast<int>(m_.cell_of[k] / nx_);
    // Internal faces: the neighbours to the right and above have higher
    // numbers, right first, so the faces come in upper-triangular order.
    if (fluid(i + 1, j)) internal(i + 1, j, {x_face(i + 1, j), k, {0, g_.face(0, i + 1, j), 1}});
    if (fluid(i, j + 1)) internal(i, j + 1, {y_face(i, j + 1), k, {1, g_.face(1, j + 1, i), 1}});
    if (!fluid(i - 1, j)) boundary({reversed(x_face(i, j)), k, {0, g_.face(0, i, j), -1}});
    if (!fluid(i + 1, j)) boundary({x_face(i + 1, j), k, {0, g_.face(0, i + 1, j), 1}});
    if (!fluid(i, j - 1)) boundary({reversed(y_face(i, j)), k, {1, g_.face(1, j, i), -1}});
    if (!fluid(i, j + 1)) boundary({y_face(i, j + 1), k, {1, g_.face(1, j + 1, i), 1}});
    const std::array<int, 4> back{node(i, j, 0), node(i, j + 1, 0), node(i + 1, j + 1, 0),
                                  node(i + 1, j, 0)};
    const std::array<int, 4> front{node(i, j, 1), node(i, j + 1, 1), node(i + 1, j + 1, 1),
                                   node(i + 1, j, 1)};
    boundary_[kFrontAndBack].push_back({back, k, kNoMacFace});
    boundary_[kFrontAndBack].push_back({reversed(front), k, kNoMacFace});
  }

  void internal(int ni, int nj, const Face& f) {
    push(f);
    m_.neighbour.push_back(cell_id_[g_.shape().index(ni, nj)]);
  }

  // A boundary face's patch is the grid's condition on it.
  void boundary(const Face& f) {
    const FaceKind kind = g_.kind(f.mac.c, f.mac.f);
    if (kind == kOutflow) {
      boundary_[kOutlet].push_back(f);
    } else if (kind == kFixed && g_.fixed_value(f.mac.c, f.mac.f) != 0.0) {
      boundary_[kInlet].push_back(f);
    } else if (kind == kFixed) {
      boundary_[kWalls].push_back(f);
    } else {
      throw InputError("OpenFOAM case: a boundary face of the grid is a free unknown");
    }
  }

  void push(const Face& f) {
    m_.faces.push_back(f.nodes);
    m_.owner.push_back(f.owner);
    if (f.mac.sign != 0) m_.mac.push_back(f.mac);
  }

  const StaggeredGrid& g_;
  const int nx_, ny_;
  FoamMesh m_;
  std::vector<int> cell_id_, node_id_;
  int n_nodes_ = 0;
  std::vector<Face> boundary_[kPatchCount];
};

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.15g", v);
  return buf;
}

std::string header(const std::string& cls, const std::string& location, const std::string& object,
                   const std::string& note = "") {
  std::string h =
      "FoamFile\n{\n    version     2.0;\n    format      ascii;\n    class       " + cls + ";\n";
  if (!note.empty()) h += "    note        \"" + note + "\";\n";
  return h + "    location    \"" + location + "\";\n    object      " + object + ";\n}\n\n";
}

void write_text(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream out(path, std::ios::binary);
  out << text;
  if (!out.flush()) throw InputError(path.string() + ": cannot write the OpenFOAM case");
}

void write_poly_mesh(const fs::path& dir, const FoamMesh& m) {
  const std::string loc = "constant/polyMesh";
  std::string text =
      header("vectorField", loc, "points") + std::to_string(m.points.size()) + "\n(\n";
  for (const auto& p : m.points)
    text += "(" + num(p[0]) + " " + num(p[1]) + " " + num(p[2]) + ")\n";
  write_text(dir / loc / "points", text + ")\n");
  text = header("faceList", loc, "faces") + std::to_string(m.faces.size()) + "\n(\n";
  for (const auto& f : m.faces)
    text += "4(" + std::to_string(f[0]) + " " + std::to_string(f[1]) + " " + std::to_string(f[2]) +
            " " + std::to_string(f[3]) + ")\n";
  write_text(dir / loc / "faces", text + ")\n");
  const std::string note = "nPoints:" + std::to_string(m.points.size()) +
                           " nCells:" + std::to_string(m.cell_of.size()) +
                           " nFaces:" + std::to_string(m.faces.size()) +
                           " nInternalFaces:" + std::to_string(m.n_internal());
  for (const char* name : {"owner", "neighbour"}) {
    const std::vector<int>& list = name[0] == 'o' ? m.owner : m.neighbour;
    text = header("labelList", loc, name, note) + std::to_string(list.size()) + "\n(\n";
    for (int v : list)
      text += std::to_string(v) + "\n";
    write_text(dir / loc / name, text + ")\n");
  }
  text = header("polyBoundaryMesh", loc, "boundary") + std::to_string(m.patches.size()) + "\n(\n";
  for (const FoamPatch& p : m.patches) {
    text += "    " + p.name + "\n    {\n        type " + p.type + ";\n";
    if (p.type != "patch") text += "        inGroups 1(" + p.type + ");\n";
    text += "        nFaces " + std::to_string(p.size) + ";\n        startFace " +
            std::to_string(p.start) + ";\n    }\n";
  }
  write_text(dir / loc / "boundary", text + ")\n");
  // Not OpenFOAM's: which plumekit cell (row-major, j * nx + i) each OpenFOAM
  // cell is, for anyone reading a kept case's fields (bench/flow_vs_openfoam.py).
  text = header("labelList", "constant", "plumekit_cells") + std::to_string(m.cell_of.size()) +
         "\n(\n";
  for (std::size_t c : m.cell_of)
    text += std::to_string(c) + "\n";
  write_text(dir / "constant" / "plumekit_cells", text + ")\n");
}

// The inlet faces' velocities: the grid's fixed normal component.
std::string inlet_velocity(const FoamMesh& m, const StaggeredGrid& grid) {
  const FoamPatch& inlet = m.patch("inlet");
  if (inlet.size == 0) return "uniform (0 0 0)";
  std::string s = "nonuniform List<vector> " + std::to_string(inlet.size) + "\n(\n";
  for (int k = 0; k < inlet.size; ++k) {
    const MacFace& f = m.mac[inlet.start + k];
    const double v = grid.fixed_value(f.c, f.f);
    s += f.c == 0 ? "(" + num(v) + " 0 0)\n" : "(0 " + num(v) + " 0)\n";
  }
  return s + ")";
}

// The largest inflow speed of the grid: the turbulence model's reference.
double inlet_reference_speed(const FoamMesh& m, const StaggeredGrid& grid) {
  double u = 0.0;
  const FoamPatch& inlet = m.patch("inlet");
  for (int k = 0; k < inlet.size; ++k)
    u = std::max(u, std::abs(grid.fixed_value(m.mac[inlet.start + k].c, m.mac[inlet.start + k].f)));
  return u;
}

struct FieldSpec {
  std::string cls, object, dims, internal;
  std::string bc[kPatchCount - 1];  // inlet, outlet, walls; frontAndBack is empty
};

void write_field(const fs::path& dir, const FieldSpec& s) {
  std::string text = header(s.cls, "0", s.object) + "dimensions      " + s.dims +
                     ";\n\ninternalField   " + s.internal + ";\n\nboundaryField\n{\n";
  for (int p = 0; p < kFrontAndBack; ++p)
    text += std::string("    ") + kPatchNames[p] + "\n    {\n        " + s.bc[p] + "\n    }\n";
  text += "    frontAndBack\n    {\n        type empty;\n    }\n}\n";
  write_text(dir / "0" / s.object, text);
}

// k and omega at the inlet: 5 % turbulence intensity, and a turbulent length
// scale of 0.07 times the arena's smaller side.
void write_turbulence_fields(const fs::path& dir, const FoamMesh& m, const StaggeredGrid& grid) {
  const double u = inlet_reference_speed(m, grid);
  const double k = 1.5 * std::pow(0.05 * u, 2);
  const double length = 0.07 * std::min(grid.shape().width, grid.shape().height);
  const double omega = std::sqrt(k) / (std::pow(0.09, 0.25) * length);
  auto scalar = [](const std::string& object, const std::string& dims, double value,
                   const std::string& wall) {
    const std::string v = "uniform " + num(value);
    return FieldSpec{"volScalarField",
                     object,
                     dims,
                     v,
                     {"type fixedValue; value " + v + ";",
                      "type inletOutlet; inletValue " + v + "; value " + v + ";",
                      "type " + wall + "; value " + v + ";"}};
  };
  write_field(dir, scalar("k", "[0 2 -2 0 0 0 0]", k, "kqRWallFunction"));
  write_field(dir, scalar("omega", "[0 0 -1 0 0 0 0]", omega, "omegaWallFunction"));
  write_field(dir, {"volScalarField",
                    "nut",
                    "[0 2 -1 0 0 0 0]",
                    "uniform 0",
                    {"type calculated; value uniform 0;", "type calculated; value uniform 0;",
                     "type nutkWallFunction; value uniform 0;"}});
}

void write_fields(const fs::path& dir, const FoamMesh& m, const StaggeredGrid& grid,
                  const OpenFoamOptions& foam) {
  write_field(dir, {"volVectorField",
                    "U",
                    "[0 1 -1 0 0 0 0]",
                    "uniform (0 0 0)",
                    {"type fixedValue; value " + inlet_velocity(m, grid) + ";",
                     "type zeroGradient;", "type noSlip;"}});
  write_field(dir,
              {"volScalarField",
               "p",
               "[0 2 -2 0 0 0 0]",
               "uniform 0",
               {"type zeroGradient;", "type fixedValue; value uniform 0;", "type zeroGradient;"}});
  if (foam.turbulence == FoamTurbulence::KOmegaSST) write_turbulence_fields(dir, m, grid);
}

void write_system(const fs::path& dir, const StaggeredGrid& grid, const OpenFoamOptions& foam) {
  const bool rans = foam.turbulence == FoamTurbulence::KOmegaSST;
  const std::string iters = std::to_string(foam.max_iterations);
  write_text(dir / "system/controlDict",
             header("dictionary", "system", "controlDict") +
                 "application simpleFoam;\nstartFrom startTime;\nstartTime 0;\nstopAt endTime;\n"
                 "endTime " +
                 iters + ";\ndeltaT 1;\nwriteControl timeStep;\nwriteInterval " + iters +
                 ";\npurgeWrite 0;\nwriteFormat ascii;\nwritePrecision 14;\n"
                 "writeCompression off;\ntimeFormat general;\ntimePrecision 8;\n"
                 "runTimeModifiable false;\n");
  // linearUpwind: second order, upwind-biased; converged at every size tried
  // (bench/openfoam/README.md). k and omega: first-order upwind, for robustness.
  write_text(dir / "system/fvSchemes",
             header("dictionary", "system", "fvSchemes") +
                 "ddtSchemes { default steadyState; }\ngradSchemes { default Gauss linear; }\n"
                 "divSchemes\n{\n    default none;\n    div(phi,U) bounded Gauss linearUpwind "
                 "grad(U);\n    div(phi,k) bounded Gauss upwind;\n    div(phi,omega) bounded "
                 "Gauss upwind;\n    div((nuEff*dev2(T(grad(U))))) Gauss linear;\n}\n"
                 "laplacianSchemes { default Gauss linear corrected; }\n"
                 "interpolationSchemes { default linear; }\nsnGradSchemes { default corrected; }\n"
                 "wallDist { method meshWave; }\n");
  const std::string tol = num(foam.tolerance);
  write_text(dir / "system/fvSolution",
             header("dictionary", "system", "fvSolution") +
                 "solvers\n{\n    p { solver GAMG; smoother GaussSeidel; tolerance 1e-12; "
                 "relTol 0.05; }\n    \"(U|k|omega)\" { solver smoothSolver; smoother "
                 "symGaussSeidel; tolerance 1e-12; relTol 0.1; }\n}\n"
                 "SIMPLE\n{\n    consistent yes;\n    nNonOrthogonalCorrectors 0;\n"
                 "    residualControl { p " +
                 tol + "; U " + tol + ";" + (rans ? " \"(k|omega)\" " + tol + ";" : "") +
                 " }\n}\nrelaxationFactors\n{\n    fields { p 1; }\n    equations { U 0.9; "
                 "\"(k|omega)\" 0.7; }\n}\n");
  // `simple` splits along the longer side (Debian's scotch is a stub).
  const bool along_x = grid.nx() >= grid.ny();
  const std::string n = std::to_string(foam.ranks);
  write_text(dir / "system/decomposeParDict",
             header("dictionary", "system", "decomposeParDict") + "numberOfSubdomains " + n +
                 ";\nmethod simple;\nsimpleCoeffs\n{\n    n (" + (along_x ? n + " 1" : "1 " + n) +
                 " 1);\n    delta 0.001;\n}\n");
}

void write_constant(const fs::path& dir, const FlowOptions& flow, const OpenFoamOptions& foam) {
  // v1912 (openfoam.com) reads turbulenceProperties, not momentumTransport.
  const std::string model = foam.turbulence == FoamTurbulence::KOmegaSST
                                ? "simulationType RAS;\nRAS\n{\n    RASModel kOmegaSST;\n    "
                                  "turbulence on;\n    printCoeffs off;\n}\n"
                                : "simulationType laminar;\n";
  write_text(dir / "constant/turbulenceProperties",
             header("dictionary", "constant", "turbulenceProperties") + model);
  write_text(dir / "constant/transportProperties",
             header("dictionary", "constant", "transportProperties") +
                 "transportModel Newtonian;\nnu " + num(flow.nu) + ";\n");
}

}  // namespace

const FoamPatch& FoamMesh::patch(const std::string& name) const {
  for (const FoamPatch& p : patches)
    if (p.name == name) return p;
  throw std::logic_error("no OpenFOAM patch " + name);
}

FoamMesh build_foam_mesh(const StaggeredGrid& grid) {
  return MeshBuilder(grid).build();
}

void write_foam_case(const fs::path& dir, const FoamMesh& mesh, const StaggeredGrid& grid,
                     const FlowOptions& flow, const OpenFoamOptions& foam) {
  write_poly_mesh(dir, mesh);
  write_fields(dir, mesh, grid, foam);
  write_system(dir, grid, foam);
  write_constant(dir, flow, foam);
}

}  // namespace plumekit::cfd
