#include "core/umfpack_lu.hpp"

#include <dlfcn.h>
#include <umfpack.h>

#include <cstring>
#include <mutex>
#include <stdexcept>
#include <string>

namespace plumekit {
namespace {

// UMFPACK's dense kernels call whatever BLAS libblas.so.3 points at. Two facts
// about OpenBLAS matter for plumekit, which runs one flow per worker thread:
//  - Its pthread build would split each call over all cores, so results would
//    depend on how many workers run at once. It is pinned to one thread.
//  - Its serial build (Debian's libopenblas0-serial, "SINGLE_THREADED") is not
//    reentrant: two threads in it at once corrupt each other's buffers, and the
//    same seed gave different winds. With it, BLAS calls take turns.
// Other BLAS libraries (netlib, BLIS, OpenBLAS pthread/OpenMP) are reentrant.
//
// True when BLAS calls must take turns. Decided once, on first use, which also
// pins OpenBLAS to one thread.
bool blas_needs_turns() {
  static const bool needs = [] {
    using SetThreads = void (*)(int);
    using GetConfig = char* (*)();
    if (auto set = reinterpret_cast<SetThreads>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads")))
      set(1);
    auto get = reinterpret_cast<GetConfig>(dlsym(RTLD_DEFAULT, "openblas_get_config"));
    const char* config = get ? get() : nullptr;
    return config && std::strstr(config, "SINGLE_THREADED");
  }();
  return needs;
}

std::mutex blas_mutex;

}  // namespace

std::unique_lock<std::mutex> blas_turn() {
  return blas_needs_turns() ? std::unique_lock<std::mutex>(blas_mutex)
                            : std::unique_lock<std::mutex>();
}

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
  const auto turn = blas_turn();
  const int status = umfpack_di_numeric(a.outerIndexPtr(), a.innerIndexPtr(), a.valuePtr(),
                                        symbolic_, &numeric_, control_.data(), info_.data());
  if (status == UMFPACK_OK) return true;
  free_numeric();
  if (status == UMFPACK_WARNING_singular_matrix) return false;
  throw std::runtime_error("UMFPACK numeric factorization failed, status " +
                           std::to_string(status));
}

void UmfpackLU::wsolve(int system, const Eigen::SparseMatrix<double>& a, const double* b, double* x,
                       double* info, int* wi, double* w) const {
  const auto turn = blas_turn();
  umfpack_di_wsolve(system, a.outerIndexPtr(), a.innerIndexPtr(), a.valuePtr(), x, b, numeric_,
                    control_.data(), info, wi, w);
}

void UmfpackLU::solve(const Eigen::SparseMatrix<double>& a, const double* b, double* x) {
  wsolve(UMFPACK_A, a, b, x, solve_info_.data(), wi_.data(), w_.data());
}

void UmfpackLU::solve_shared(const Eigen::SparseMatrix<double>& a, const double* b, double* x,
                             bool transpose) const {
  std::vector<int> wi(static_cast<std::size_t>(a.rows()));
  std::vector<double> w(control_[UMFPACK_IRSTEP] > 0 ? 5 * wi.size() : wi.size());
  std::vector<double> info(UMFPACK_INFO);
  wsolve(transpose ? UMFPACK_At : UMFPACK_A, a, b, x, info.data(), wi.data(), w.data());
}

}  // namespace plumekit
