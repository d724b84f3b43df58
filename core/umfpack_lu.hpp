#pragma once
// A thin owner of UMFPACK's symbolic and numeric objects for one sparsity
// pattern: analyse once, factorize many times, solve with preallocated
// workspace. Eigen's UmfPackLU would do, but hides UMFPACK's Info (fill,
// flops) and allocates workspace on every solve.
#include <Eigen/SparseCore>
#include <array>
#include <mutex>
#include <vector>

namespace plumekit {

// Holds the BLAS lock for the duration of one call into a library that runs
// BLAS (UMFPACK, MUMPS) where the BLAS is not reentrant, and pins OpenBLAS to
// one thread on first use (umfpack_lu.cpp says why).
std::unique_lock<std::mutex> blas_turn();

class UmfpackLU {
 public:
  UmfpackLU();
  ~UmfpackLU();
  UmfpackLU(const UmfpackLU&) = delete;
  UmfpackLU& operator=(const UmfpackLU&) = delete;

  // UMFPACK's Control array (UMFPACK_STRATEGY, UMFPACK_ORDERING, ...).
  double& control(int key) { return control_[key]; }
  // UMFPACK's Info array of the last analysis or factorization.
  double info(int key) const { return info_[key]; }

  // Symbolic analysis of the pattern; redone only when the pattern changes.
  void analyze(const Eigen::SparseMatrix<double>& a);
  // Numeric factorization of a matrix with the analysed pattern. False when
  // the matrix is singular.
  bool factorize(const Eigen::SparseMatrix<double>& a);
  // x = A^-1 b with the last factorization (x and b must not alias).
  void solve(const Eigen::SparseMatrix<double>& a, const double* b, double* x);
  // x = A^-1 b, or A'^-1 b if `transpose`, with workspace of its own: safe to
  // call from several threads at once on one factorization.
  void solve_shared(const Eigen::SparseMatrix<double>& a, const double* b, double* x,
                    bool transpose) const;

 private:
  void free_numeric();
  // UMFPACK's solve of `system` (UMFPACK_A or UMFPACK_At) with the given
  // workspace, taking the BLAS turn when needed.
  void wsolve(int system, const Eigen::SparseMatrix<double>& a, const double* b, double* x,
              double* info, int* wi, double* w) const;
  std::vector<double> control_, info_, solve_info_;
  std::vector<int> wi_;
  std::vector<double> w_;
  void* symbolic_ = nullptr;
  void* numeric_ = nullptr;
};

}  // namespace plumekit
