#pragma once
// Solves the Newton systems J dx = b of the MAC equations (nullspace method):
// the velocity correction is split into a particular part that satisfies the
// continuity rows and a discretely divergence-free part C z, where C is the
// discrete curl of a streamfunction that lives on the grid nodes (one unknown
// per node group: nodes joined by fixed faces, such as an obstacle's outline
// or the walls, share one value). Projecting the momentum rows onto C removes
// the pressure, so UMFPACK factorizes a matrix K = L' A C with one unknown per
// node instead of three per cell. On the 5 cm benchmark grid, K's LU has 1.5 M
// entries against the coupled matrix's 5 M, and takes a fifth of the flops.
//
// The pressure correction then follows from the momentum rows of a spanning
// tree of cell-to-cell faces rooted at the outlet, in one sweep. The outlet's
// fixed pressure keeps the plain curl projection from cancelling the pressure
// at outlet nodes; L' = C'(I - G R) corrects for it with the outlet faces' own
// momentum rows (R maps each outlet face's row to its cell's pressure).
//
// The step equals the coupled solve's to round-off. It needs every fluid cell
// to reach the outlet (or, in a closed box, the pinned cell) through fluid;
// applicable() says whether it does.
#include <Eigen/SparseCore>
#include <memory>
#include <vector>

#include "cfd/linear_solver.hpp"
#include "cfd/single_precision_lu.hpp"
#include "cfd/staggered_grid.hpp"
#include "core/umfpack_lu.hpp"

namespace plumekit::cfd {

// K's LU: UMFPACK in double, or MUMPS in single precision (single_precision_lu.hpp).
enum class ReducedLU {
  BySize,  // single precision from kSinglePrecisionFrom unknowns, where MUMPS is built in
  Double,
  Single,  // where MUMPS is built in (else double)
};
// K's size from which BySize factorizes in single precision: above every grid of
// a 10 x 4 m map at the default 5 cm (cluttered-1's K has 14 518 unknowns), so
// the shipped and random maps' default flows (and the evaluations made with
// them) are those of the double LU, bit for bit. Building-scale maps' coarse
// grids (20 000 to 100 000 unknowns) factor about twice as fast in single
// precision: tb3_world's 10 cm grid, 6.8 -> 6.3 s for the whole 5 cm solve.
constexpr int kSinglePrecisionFrom = 20000;

class NullSpaceSolver : public LinearSolver {
 public:
  // `jacobian` holds the values of some Newton matrix of `grid`'s equations
  // (the continuity and pressure entries, which never change, are read here).
  NullSpaceSolver(const StaggeredGrid& grid, const Eigen::SparseMatrix<double>& jacobian,
                  ReducedLU lu = ReducedLU::BySize);

  bool applicable() const { return applicable_; }
  // Unknowns of the reduced matrix K (node groups).
  int reduced_size() const { return static_cast<int>(curl_.cols()); }
  // Whether K is factorized in single precision.
  bool single_precision() const { return single_ != nullptr; }

  const char* name() const override { return "nullspace"; }
  // Factorizes K for this Jacobian (same pattern as the constructor's). False
  // when K is singular.
  bool factorize(const Eigen::SparseMatrix<double>& jacobian) override;
  // x = J^-1 b with the last factorization, where J is the matrix given to
  // factorize() (x and b must not alias).
  void solve(const Eigen::SparseMatrix<double>& jacobian, const double* b, double* x) override;

 private:
  // One cell of the spanning tree, in breadth-first order from the roots.
  struct TreeCell {
    int cell;             // grid cell index
    int p;                // pressure column (= continuity row)
    int face;             // velocity column of the tree face; -1 for a pinned root
    int parent;           // parent's pressure column; -1 for a root
    double d_face = 0.0;  // continuity coefficient of the tree face
    // Pressure coefficients in the tree face's momentum row; a pinned root's
    // g_own is the coefficient of its own row (its pressure alone).
    double g_own = 0.0, g_parent = 0.0;
  };
  // A continuity row: up to four (velocity column, coefficient) entries.
  struct ContinuityRow {
    int count = 0;
    int col[4];
    double coef[4];
  };

  // The constructor's steps; each false step leaves the solver not applicable.
  // False when a column holds more than a MAC continuity row's four entries.
  bool read_continuity_rows(const Eigen::SparseMatrix<double>& jacobian);
  // False when the tree cannot reach every fluid cell, or a tree face cannot
  // carry its cell's flux or pressure.
  bool build_tree(const StaggeredGrid& grid, const Eigen::SparseMatrix<double>& jacobian);
  void add_roots(const StaggeredGrid& grid, const Eigen::SparseMatrix<double>& jacobian,
                 std::vector<char>& reached);
  void add_root(const StaggeredGrid& grid, const Eigen::SparseMatrix<double>& jacobian,
                std::vector<char>& reached, std::size_t cell, int face);
  void build_curl(const StaggeredGrid& grid);
  // Makes L'; returns C' G (G: J's pressure columns), which the check reuses.
  Eigen::SparseMatrix<double> build_projection(const Eigen::SparseMatrix<double>& jacobian);
  // D C = 0 and L' G = 0, to round-off.
  bool operators_check(const GridShape& s, const Eigen::SparseMatrix<double>& jacobian,
                       const Eigen::SparseMatrix<double>& curl_g) const;
  // The coefficient of velocity column `col` in continuity row `p`.
  double continuity_coef(int p, int col) const;
  // The single-precision path forms K in place (form_reduced) into a pattern
  // built once (build_reduced_pattern): Eigen's products would hold J C and a
  // row-major copy of K beside the LU (about 100 MB on tb3_world at 5 cm). The
  // double path keeps Eigen's products, whose sums the shipped maps' flows
  // were made with, bit for bit.
  bool factorize_single(const Eigen::SparseMatrix<double>& jacobian);
  void build_reduced_pattern(const Eigen::SparseMatrix<double>& jacobian);
  void form_reduced(const Eigen::SparseMatrix<double>& jacobian);

  int n_ = 0, n_mom_ = 0;
  bool applicable_ = false;
  std::vector<TreeCell> tree_;
  std::vector<ContinuityRow> continuity_;  // indexed by p - n_mom
  Eigen::SparseMatrix<double> curl_;       // n x groups: velocity rows only
  Eigen::SparseMatrix<double> left_;       // groups x n: L' (momentum columns only)
  Eigen::SparseMatrix<double> reduced_;    // K = L' J C
  Eigen::Index analysed_nonzeros_ = -1;    // K's pattern size at the last analysis
  UmfpackLU lu_;
  std::unique_ptr<SinglePrecisionLU> single_;  // instead of lu_, when chosen
  std::vector<int> slot_, touched_;            // form_reduced's workspace
  std::vector<double> jc_;
  std::vector<char> in_column_;
  std::vector<double> du_, t_, r_, z_, rz_;
};

}  // namespace plumekit::cfd
