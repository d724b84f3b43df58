#include "cfd/single_precision_lu.hpp"

#include <algorithm>
#include <cmath>
#include <mutex>
#include <stdexcept>
#include <string>

#include "core/umfpack_lu.hpp"

#ifdef PLUMEKIT_HAVE_MUMPS
#include <smumps_c.h>
#endif

namespace plumekit::cfd {

#ifdef PLUMEKIT_HAVE_MUMPS

namespace {
constexpr int kUseCommWorld = -987654;  // MUMPS's sequential "communicator"
constexpr int kSingular = -10;          // INFOG(1) of a numerically singular matrix
constexpr int kWorkspaceShort = -9;     // INFOG(1) when the estimated workspace was short
}  // namespace

// Sequential MUMPS is not reentrant: its Fortran modules (the load balancer, the out-of-core
// layer) and the MPI stub it links keep process-wide state, so two instances working at once in
// two threads corrupt the heap ("PB allocation in SMUMPS_LOAD_INIT", then a crash; seen with
// `dataset generate -j 2` on random buildings, whose flows are large enough to use MUMPS). Every
// call takes its turn, whatever the BLAS.
namespace {
std::mutex mumps_mutex;
}  // namespace

struct SinglePrecisionLU::Mumps {
  SMUMPS_STRUC_C id{};
  void call(int job) {
    id.job = job;
    const std::lock_guard<std::mutex> one_at_a_time(mumps_mutex);
    const auto turn = blas_turn();
    smumps_c(&id);
  }
};

bool single_precision_lu_available() {
  return true;
}

SinglePrecisionLU::SinglePrecisionLU() : mumps_(std::make_unique<Mumps>()) {
  SMUMPS_STRUC_C& id = mumps_->id;
  id.comm_fortran = kUseCommWorld;
  id.par = 1;  // the host works (there is no other process)
  id.sym = 0;  // unsymmetric
  mumps_->call(-1);
  // ICNTL(k) is icntl[k-1]: no output (1-4), AMD ordering (7: METIS took 1 s on
  // the tb3_world matrix, five times AMD's analysis, for 20 % fewer flops),
  // sequential analysis (28).
  id.icntl[0] = id.icntl[1] = id.icntl[2] = -1;
  id.icntl[3] = 0;
  id.icntl[6] = 0;
  id.icntl[27] = 1;
}

SinglePrecisionLU::~SinglePrecisionLU() {
  mumps_->call(-2);
}

void SinglePrecisionLU::analyze(const Eigen::SparseMatrix<double>& a) {
  rows_.resize(a.nonZeros());
  cols_.resize(a.nonZeros());
  for (int c = 0; c < a.outerSize(); ++c)
    for (int k = a.outerIndexPtr()[c]; k < a.outerIndexPtr()[c + 1]; ++k) {
      rows_[k] = a.innerIndexPtr()[k] + 1;
      cols_[k] = c + 1;
    }
  values_.resize(a.nonZeros());
  rhs_.resize(a.rows());
  SMUMPS_STRUC_C& id = mumps_->id;
  id.n = static_cast<int>(a.rows());
  id.nnz = a.nonZeros();
  id.irn = rows_.data();
  id.jcn = cols_.data();
  id.a = values_.data();
  mumps_->call(1);
  if (id.infog[0] < 0)
    throw std::runtime_error("MUMPS analysis failed, INFOG(1) " + std::to_string(id.infog[0]));
}

bool SinglePrecisionLU::factorize(const Eigen::SparseMatrix<double>& a) {
  std::copy(a.valuePtr(), a.valuePtr() + a.nonZeros(), values_.begin());
  SMUMPS_STRUC_C& id = mumps_->id;
  for (int attempt = 0; attempt < 4; ++attempt) {
    mumps_->call(2);
    if (id.infog[0] != kWorkspaceShort) break;
    id.icntl[13] *= 2;  // ICNTL(14): more workspace over the estimate, and again
  }
  if (id.infog[0] == kSingular) return false;
  if (id.infog[0] < 0)
    throw std::runtime_error("MUMPS factorization failed, INFOG(1) " + std::to_string(id.infog[0]));
  return true;
}

void SinglePrecisionLU::solve(const double* b, double* x) {
  // Scaled to a largest entry of 1, so that float neither overflows nor
  // flushes small right-hand sides to zero.
  const std::size_t n = rhs_.size();
  double scale = 0.0;
  for (std::size_t k = 0; k < n; ++k)
    scale = std::max(scale, std::abs(b[k]));
  if (scale == 0.0) {
    std::fill(x, x + n, 0.0);
    return;
  }
  for (std::size_t k = 0; k < n; ++k)
    rhs_[k] = static_cast<float>(b[k] / scale);
  SMUMPS_STRUC_C& id = mumps_->id;
  id.rhs = rhs_.data();
  id.nrhs = 1;
  id.lrhs = static_cast<int>(n);
  mumps_->call(3);
  if (id.infog[0] < 0)
    throw std::runtime_error("MUMPS solve failed, INFOG(1) " + std::to_string(id.infog[0]));
  for (std::size_t k = 0; k < n; ++k)
    x[k] = scale * rhs_[k];
}

double SinglePrecisionLU::factor_entries() const {
  return mumps_->id.infog[28];
}

#else  // no MUMPS: never made (single_precision_lu_available() is false)

struct SinglePrecisionLU::Mumps {};
bool single_precision_lu_available() {
  return false;
}
SinglePrecisionLU::SinglePrecisionLU() {
  throw std::logic_error("built without MUMPS");
}
SinglePrecisionLU::~SinglePrecisionLU() = default;
void SinglePrecisionLU::analyze(const Eigen::SparseMatrix<double>&) {}
bool SinglePrecisionLU::factorize(const Eigen::SparseMatrix<double>&) {
  return false;
}
void SinglePrecisionLU::solve(const double*, double*) {}
double SinglePrecisionLU::factor_entries() const {
  return 0.0;
}

#endif

}  // namespace plumekit::cfd

#ifdef PLUMEKIT_HAVE_MUMPS
// MUMPS's solve phase multiplies each front's block by the right-hand side
// with SGEMM even for one right-hand side (its BLAS-2 path is a build option
// Debian's package leaves off), and OpenBLAS 0.3.21's SGEMM copies the whole
// block into a packed buffer first: on tb3_world and depot at 5 cm every
// chord step's solve spent more time packing than multiplying. This SGEMM,
// which the dynamic linker gives MUMPS in place of the BLAS library's, sends
// one-column products to SGEMV (the same sums, no copy) and everything else
// to the library: 5.4 -> 5.1 s on depot, 6.1 -> 5.7 s on tb3_world (medians
// of three). K > 0 and M > 0 only: SGEMV skips the beta scaling when a
// dimension is zero, where SGEMM applies it.
#include <dlfcn.h>

#include <cstdio>
#include <cstdlib>

extern "C" {
using SgemmFunction = void (*)(const char*, const char*, const int*, const int*, const int*,
                               const float*, const float*, const int*, const float*, const int*,
                               const float*, float*, const int*, std::size_t, std::size_t);
using SgemvFunction = void (*)(const char*, const int*, const int*, const float*, const float*,
                               const int*, const float*, const int*, const float*, float*,
                               const int*, std::size_t);

static void* blas_symbol(void* handle, const char* name) {
  void* f = dlsym(handle, name);
  if (!f) {
    std::fprintf(stderr, "plumekit: no BLAS %s in this process\n", name);
    std::abort();
  }
  return f;
}

void sgemm_(const char* transa, const char* transb, const int* m, const int* n, const int* k,
            const float* alpha, const float* a, const int* lda, const float* b, const int* ldb,
            const float* beta, float* c, const int* ldc, std::size_t transa_length,
            std::size_t transb_length) {
  if (*n == 1 && *m > 0 && *k > 0) {
    static const auto sgemv = reinterpret_cast<SgemvFunction>(blas_symbol(RTLD_DEFAULT, "sgemv_"));
    // op(B) is one column: B's first column, or its first row when transposed.
    const int incx = (*transb == 'N' || *transb == 'n') ? 1 : *ldb;
    const bool transposed = !(*transa == 'N' || *transa == 'n');
    const int rows = transposed ? *k : *m, cols = transposed ? *m : *k, incy = 1;
    sgemv(transa, &rows, &cols, alpha, a, lda, b, &incx, beta, c, &incy, transa_length);
    return;
  }
  static const auto sgemm = reinterpret_cast<SgemmFunction>(blas_symbol(RTLD_NEXT, "sgemm_"));
  sgemm(transa, transb, m, n, k, alpha, a, lda, b, ldb, beta, c, ldc, transa_length, transb_length);
}
}
#endif
