#include "cfd/umfpack_lu.hpp"

#include <stdexcept>
#include <string>

#include <umfpack.h>

namespace plumekit::cfd {

UmfpackLU::UmfpackLU() : control_(UMFPACK_CONTROL), info_(UMFPACK_INFO), solve_info_(UMFPACK_INFO) {
  umfpack_di_defaults(control_.data());
}

UmfpackLU::~UmfpackLU() {
  free_numeric();
  if (symbolic_) umfpack_di_free_symbolic(&symbolic_);
}

void UmfpackLU::free_numeric() {
  if (numeric_) umfpack_di_free_numeric(&numeric_);
}

void UmfpackLU::analyze(const Eigen::SparseMatrix<double>& a) {
  free_numeric();
  if (symbolic_) umfpack_di_free_symbolic(&symbolic_);
  const int status = umfpack_di_symbolic(static_cast<int>(a.rows()), static_cast<int>(a.cols()),
                                         a.outerIndexPtr(), a.innerIndexPtr(), a.valuePtr(),
                                         &symbolic_, control_.data(), info_.data());
  if (status != UMFPACK_OK)
    throw std::runtime_error("UMFPACK symbolic analysis failed, status " + std::to_string(status));
  const std::size_t n = static_cast<std::size_t>(a.rows());
  wi_.resize(n);
  w_.resize(control_[UMFPACK_IRSTEP] > 0 ? 5 * n : n);
}

bool UmfpackLU::factorize(const Eigen::SparseMatrix<double>& a) {
  free_numeric();
  const int status = umfpack_di_numeric(a.outerIndexPtr(), a.innerIndexPtr(), a.valuePtr(),
                                        symbolic_, &numeric_, control_.data(), info_.data());
  if (status == UMFPACK_OK) return true;
  free_numeric();
  if (status == UMFPACK_WARNING_singular_matrix) return false;
  throw std::runtime_error("UMFPACK numeric factorization failed, status " +
                           std::to_string(status));
}

void UmfpackLU::solve(const Eigen::SparseMatrix<double>& a, const double* b, double* x) {
  umfpack_di_wsolve(UMFPACK_A, a.outerIndexPtr(), a.innerIndexPtr(), a.valuePtr(), x, b, numeric_,
                    control_.data(), solve_info_.data(), wi_.data(), w_.data());
}

}  // namespace plumekit::cfd
