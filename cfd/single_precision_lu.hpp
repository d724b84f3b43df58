#pragma once
// A single-precision sparse LU (MUMPS's smumps, sequential library) of a
// double matrix, for the large reduced systems of the nullspace solver
// (docs/design/flow-solver.md, "Building scale: how the solver got there"):
// half the memory of a double LU and about half the factorization time. Its
// solves are accurate to about 1e-2 relative on the 5 cm tb3_world matrix,
// which Newton's chord steps absorb: every step is followed by a residual in
// double. Built only when CMake finds MUMPS
// (PLUMEKIT_HAVE_MUMPS); single_precision_lu_available() says so.
#include <Eigen/SparseCore>
#include <memory>
#include <vector>

namespace plumekit::cfd {

bool single_precision_lu_available();

class SinglePrecisionLU {
 public:
  SinglePrecisionLU();
  ~SinglePrecisionLU();
  SinglePrecisionLU(const SinglePrecisionLU&) = delete;
  SinglePrecisionLU& operator=(const SinglePrecisionLU&) = delete;

  // Ordering and symbolic analysis of a square matrix's pattern.
  void analyze(const Eigen::SparseMatrix<double>& a);
  // Numeric factorization of a matrix with the analysed pattern, rounded to
  // float. False when it is singular.
  bool factorize(const Eigen::SparseMatrix<double>& a);
  // x = A^-1 b with the last factorization (x and b may alias).
  void solve(const double* b, double* x);
  // Entries of the factors (MUMPS's INFOG(29)).
  double factor_entries() const;

 private:
  struct Mumps;
  std::unique_ptr<Mumps> mumps_;
  std::vector<int> rows_, cols_;  // 1-based coordinates of the pattern
  std::vector<float> values_, rhs_;
};

}  // namespace plumekit::cfd
