#include "cfd/linear_solver.hpp"

#include "cfd/coupled_solver.hpp"
#include "cfd/nullspace_solver.hpp"

namespace plumekit::cfd {

std::unique_ptr<LinearSolver> make_linear_solver(LinearSolverKind kind, const StaggeredGrid& grid,
                                                 const Eigen::SparseMatrix<double>& jacobian) {
  if (kind == LinearSolverKind::Nullspace) {
    auto nullspace = std::make_unique<NullSpaceSolver>(grid, jacobian);
    if (nullspace->applicable()) return nullspace;
  }
  return std::make_unique<CoupledSolver>(grid, jacobian);
}

}  // namespace plumekit::cfd
