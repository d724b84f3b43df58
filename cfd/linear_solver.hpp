#pragma once
// The Newton systems J dx = b of one grid's flow equations, solved by one of
// two methods with the same steps to round-off (docs/design/flow-solver.md, "Numerics"):
//  - NullSpaceSolver (nullspace_solver.hpp): the divergence-free subspace, one
//    unknown per grid node; the default, and far cheaper to factorize;
//  - CoupledSolver (coupled_solver.hpp): UMFPACK on the full (u, v, p) matrix
//    with its rows paired for a full diagonal; used when asked for, and where
//    the nullspace method does not apply.
#include <Eigen/SparseCore>
#include <memory>

#include "cfd/options.hpp"
#include "cfd/staggered_grid.hpp"

namespace plumekit::cfd {

class LinearSolver {
 public:
  virtual ~LinearSolver() = default;
  // "nullspace" or "coupled" (FlowSummary::linear_solver).
  virtual const char* name() const = 0;
  // Factorizes J, whose pattern is the one the solver was made with. False when
  // J is singular.
  virtual bool factorize(const Eigen::SparseMatrix<double>& jacobian) = 0;
  // x = J^-1 b with the last factorization, where `jacobian` is the matrix given
  // to factorize() (x and b must not alias).
  virtual void solve(const Eigen::SparseMatrix<double>& jacobian, const double* b, double* x) = 0;
};

// The solver `kind` names for `grid`'s Newton matrices, made from their
// (fixed) pattern and the constant entries of `jacobian`: the nullspace solver
// where asked for and applicable, else the coupled one.
std::unique_ptr<LinearSolver> make_linear_solver(LinearSolverKind kind, const StaggeredGrid& grid,
                                                 const Eigen::SparseMatrix<double>& jacobian);

}  // namespace plumekit::cfd
