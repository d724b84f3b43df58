#include "cfd/coupled_solver.hpp"

#include <umfpack.h>

namespace plumekit::cfd {

CoupledSolver::CoupledSolver(const StaggeredGrid& grid, const Eigen::SparseMatrix<double>& jacobian)
    : pairing_(grid, jacobian), pb_(static_cast<std::size_t>(jacobian.rows())) {
  // No iterative refinement: Newton's next residual does that job, and each
  // refinement step would cost another pair of triangular solves.
  lu_.control(UMFPACK_IRSTEP) = 0;
  // The rows are paired so that the matrix has a full diagonal, which lets
  // UMFPACK order A + A' and pivot on the diagonal (diagonal_pairing.hpp).
  lu_.control(UMFPACK_STRATEGY) = UMFPACK_STRATEGY_SYMMETRIC;
  lu_.analyze(pairing_.permuted(jacobian));
}

bool CoupledSolver::factorize(const Eigen::SparseMatrix<double>& jacobian) {
  return lu_.factorize(pairing_.permuted(jacobian));
}

void CoupledSolver::solve(const Eigen::SparseMatrix<double>&, const double* b, double* x) {
  // (P J) x = P b has J's own solution; the permuted matrix holds J's values
  // since the last factorize().
  pairing_.permute(b, pb_.data());
  lu_.solve(pairing_.permuted_matrix(), pb_.data(), x);
}

}  // namespace plumekit::cfd
