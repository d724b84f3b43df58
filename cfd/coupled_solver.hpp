#pragma once
// The coupled Newton solve: UMFPACK on the full (u, v, p) matrix, its rows
// paired for a full diagonal (diagonal_pairing.hpp) so that UMFPACK can order
// A + A' and pivot on the diagonal. The pattern is analysed once.
#include "cfd/diagonal_pairing.hpp"
#include "cfd/linear_solver.hpp"
#include "core/umfpack_lu.hpp"

namespace plumekit::cfd {

class CoupledSolver : public LinearSolver {
 public:
  // Pairs the rows and analyses the pattern, with `jacobian`'s values.
  CoupledSolver(const StaggeredGrid& grid, const Eigen::SparseMatrix<double>& jacobian);

  const char* name() const override { return "coupled"; }
  bool factorize(const Eigen::SparseMatrix<double>& jacobian) override;
  void solve(const Eigen::SparseMatrix<double>& jacobian, const double* b, double* x) override;

 private:
  DiagonalPairing pairing_;
  UmfpackLU lu_;
  std::vector<double> pb_;  // P b
};

}  // namespace plumekit::cfd
