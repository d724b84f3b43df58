#pragma once
// The coupled Newton matrix has no diagonal in its continuity rows (the
// pressure does not appear in its own cell's continuity equation). UMFPACK's
// unsymmetric strategy copes by searching rows for pivots, which is most of
// its factorization time on these grids. Swapping each cell's continuity row
// with the momentum row of one of the cell's free faces gives a matrix with a
// full diagonal (the face's momentum row holds the cell's pressure, and the
// cell's continuity row holds the face), so UMFPACK's symmetric strategy can
// order A + A' and pivot on the diagonal. Solving (P J) x = P b gives the same
// x; only the rows are reordered.
#include <Eigen/SparseCore>
#include <vector>

#include "cfd/staggered_grid.hpp"

namespace plumekit::cfd {

class DiagonalPairing {
 public:
  // Pairs the cells of `grid` with faces, given the Jacobian's fixed pattern.
  DiagonalPairing(const StaggeredGrid& grid, const Eigen::SparseMatrix<double>& jacobian);

  // P J, with the values of `jacobian` (whose pattern must be the one given
  // to the constructor). The returned matrix keeps its pattern between calls.
  const Eigen::SparseMatrix<double>& permuted(const Eigen::SparseMatrix<double>& jacobian);
  // P J as last returned by permuted().
  const Eigen::SparseMatrix<double>& permuted_matrix() const { return permuted_; }
  // P b.
  void permute(const double* b, double* pb) const;
  // Cells whose continuity row found no face to pair with (0 on every grid
  // seen; such a row simply keeps its zero diagonal).
  int unpaired() const { return unpaired_; }

 private:
  // The pattern of P J and the map of J's values into it.
  void build_permuted_pattern(const Eigen::SparseMatrix<double>& jacobian);

  std::vector<int> source_row_;  // row r of P J is row source_row_[r] of J
  std::vector<int> value_map_;   // value k of J goes to value value_map_[k] of P J
  Eigen::SparseMatrix<double> permuted_;
  int unpaired_ = 0;
};

}  // namespace plumekit::cfd
